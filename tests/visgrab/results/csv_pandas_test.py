#!/usr/bin/env python3
"""pandas.read_csv(path) with NO options reads every result CSV the project writes, giving the
values the C++ side wrote (CTest: csv_pandas_test).

usage: csv_pandas_test.py FIXTURE

FIXTURE (csv_pandas_fixture) writes trials.csv and run.csv through ResultsWriter with text that
needs every RFC 4180 rule (commas, quotes, CR, LF, CR LF, backslashes, leading blanks, unicode),
the report's CSV tables of that run and a stages.csv, plus truth.json: each file's columns and
rows. Every cell pandas reads is compared with the truth: strings exactly; an empty field or a
NaN is pandas' NaN; numbers within 1e-14 relative, because pandas' default float parser is not
correctly rounded (0.06666666666666667 reads as 0.0666666666666666, five units in the last place
off) although the files hold each double's shortest round-trip text. A second read with
float_precision="round_trip" must then give every number exactly. Exit 0 when all match, 1
otherwise, 77 (skipped) when pandas cannot be imported.
"""

import json
import math
import numbers
import os
import subprocess
import sys
import tempfile

try:
    import pandas as pd
except ImportError as error:
    print(f"SKIP: pandas cannot be imported by {sys.executable}: {error} "
          "(Debian: apt-get install python3-pandas)")
    sys.exit(77)


def same_number(read, written, exact):
    """pandas' number against the written one: equal, or within 1e-14 relative (default parser)."""
    if exact:
        return read == written
    return math.isclose(read, written, rel_tol=1e-14, abs_tol=0.0)


def cell_matches(cell, truth, numeric_column, exact):
    """Whether pandas' cell is the value the C++ side wrote."""
    if truth is None or truth == "":
        # pandas' own rule: an empty field is missing (NaN).
        return bool(pd.isna(cell))
    if pd.isna(cell):
        return False
    if isinstance(truth, numbers.Number):
        return isinstance(cell, numbers.Number) and same_number(float(cell), float(truth), exact)
    if numeric_column:
        # A number the C++ reader gave back as text (the report's tables).
        return same_number(float(cell), float(truth), exact)
    return isinstance(cell, str) and cell == truth


def check_file(directory, table, exact):
    """Differences between one file as pandas reads it and its truth (a list of strings): with no
    options, or with exact float parsing only."""
    path = os.path.join(directory, table["file"])
    if exact:
        frame = pd.read_csv(path, float_precision="round_trip")
    else:
        frame = pd.read_csv(path)  # no options: this is the point of the test
    problems = []
    if list(frame.columns) != table["columns"]:
        return [f"{table['file']}: columns {list(frame.columns)}, expected {table['columns']}"]
    if len(frame) != len(table["rows"]):
        return [f"{table['file']}: {len(frame)} rows, expected {len(table['rows'])}"]
    for r, row in enumerate(table["rows"]):
        for c, truth in enumerate(row):
            column = table["columns"][c]
            cell = frame.iat[r, c]
            numeric = pd.api.types.is_numeric_dtype(frame[column])
            if not cell_matches(cell, truth, numeric, exact):
                how = " (float_precision='round_trip')" if exact else ""
                problems.append(f"{table['file']} row {r + 1} column {column}: pandas read "
                                f"{cell!r}{how}, the C++ side wrote {truth!r}")
    return problems


def main(argv):
    if len(argv) != 1:
        print(__doc__.splitlines()[2], file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory() as directory:
        subprocess.run([argv[0], directory], check=True)
        with open(os.path.join(directory, "truth.json"), encoding="utf-8") as f:
            truth = json.load(f)
        files = [t["file"] for t in truth["files"]]
        expected = {"results/trials.csv", "results/run.csv", "report/distribution.csv",
                    "report/quality.csv", "report/attempts.csv", "report/first_success.csv",
                    "report/objects.csv", "report/success.csv", "report/comparisons.csv",
                    "report/robust.csv", "stages.csv"}
        if set(files) != expected:
            print(f"the fixture wrote {sorted(files)}, expected {sorted(expected)}")
            return 1
        problems = []
        cells = 0
        for table in truth["files"]:
            for exact in (False, True):
                problems += check_file(directory, table, exact)
            cells += sum(len(row) for row in table["rows"])
        # The nasty text really is there (a fixture without it would prove nothing).
        trials = pd.read_csv(os.path.join(directory, "results/trials.csv"))
        details = set(trials["detail"].dropna())
        for needed in ("x\ny", "cr\rz", "crlf\r\nq", "back\\slash \\n", " lead", "say \"hi\""):
            if needed not in details:
                problems.append(f"trials.csv: no detail {needed!r} (the fixture changed?)")
        if not any("\n" in str(m) for m in trials["method"]):
            problems.append("trials.csv: no method with a line break (the fixture changed?)")
        for p in problems:
            print(p)
        print(f"{len(files)} files, {cells} cells compared, {len(problems)} problems")
        return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
