#!/usr/bin/env python3
"""Compare the verdicts of two runs of the same grasps: visgrab results' trials.csv files.

usage: scripts/compare-trials.py A/trials.csv B/trials.csv [--list N]

Trials are matched by (scene, method, grasp). Prints the trials only in one file, each run's
outcome counts, the verdicts that differ (as "A -> B" pairs, most frequent first, and the first N
of them with --list) and the simulated time of each run. Exit 0 when both files are read (the
verdicts may differ), 1 when a file cannot be read or is not a trials.csv, 2 on a usage mistake.
Reads every trials.csv version: 4 (RFC 4180, what `visgrab run` writes), 3 (the same without
closing_capped) and the older 1 and 2.
docs/performance.md ("Where a trial's time goes") uses it to say how far a change moves verdicts.
"""

import argparse
import collections
import csv
import io
import re
import sys

KEY = ("scene", "method", "grasp")
NEEDED = KEY + ("outcome", "simulated_time")


class BadFile(Exception):
    """A file that is not a readable trials.csv; the message names file and line."""


def undo_backslash_escapes(text):
    """A field of a version 1 or 2 trials.csv: quoted fields escaped \\, line feed and carriage
    return as \\\\, \\n, \\r (an unquoted field never held a backslash)."""
    return re.sub(r"\\(.)", lambda m: {"n": "\n", "r": "\r"}.get(m.group(1), m.group(1)), text)


def load(path):
    """The trials of one trials.csv, keyed by (scene, method, grasp).

    Version 3 is RFC 4180 (a record may span lines); versions 1 and 2 start with the comment line
    "# visgrab trials N" and escape with backslashes.
    """
    try:
        with open(path, newline="", encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        raise BadFile(f"{path}: cannot read: {e.strerror}") from e
    except UnicodeDecodeError as e:
        raise BadFile(f"{path}: not UTF-8 text: {e.reason}") from e
    # Older versions: comment lines ("# visgrab trials 2") come before the header.
    first = 0
    while text.startswith("#"):
        end = text.find("\n")
        text = "" if end < 0 else text[end + 1:]
        first += 1
    legacy = first > 0
    reader = csv.DictReader(io.StringIO(text, newline=""))
    missing = [c for c in NEEDED if c not in (reader.fieldnames or [])]
    if missing:
        raise BadFile(f"{path}:{first + 1}: expected a trials.csv header with "
                      f"{', '.join(NEEDED)}; missing {', '.join(missing)}")
    trials = {}
    start = first + 2  # the line where the next record starts
    try:
        for row in reader:
            number, start = start, first + reader.line_num + 1
            if None in row or None in row.values():
                raise BadFile(f"{path}:{number}: wrong number of fields (expected "
                              f"{len(reader.fieldnames)})")
            if legacy:
                row = {k: undo_backslash_escapes(v) for k, v in row.items()}
            key = tuple(row[c] for c in KEY)
            if key in trials:
                raise BadFile(f"{path}:{number}: trial {'/'.join(key)} appears twice")
            try:
                row["simulated_time"] = float(row["simulated_time"])
            except (TypeError, ValueError) as e:
                raise BadFile(f"{path}:{number}: simulated_time '{row['simulated_time']}' "
                              "is not a number") from e
            trials[key] = row
    except csv.Error as e:
        raise BadFile(f"{path}:{start}: {e}") from e
    return trials


def compare(a, b):
    """The comparison of two loaded runs as a dict (see main() for what is printed)."""
    common = sorted(set(a) & set(b))
    flips = collections.Counter()
    changed = []
    for key in common:
        pair = (a[key]["outcome"], b[key]["outcome"])
        if pair[0] != pair[1]:
            flips[pair] += 1
            changed.append((key, pair))
    return {
        "common": len(common),
        "only_a": len(set(a) - set(b)),
        "only_b": len(set(b) - set(a)),
        "outcomes_a": collections.Counter(r["outcome"] for r in a.values()),
        "outcomes_b": collections.Counter(r["outcome"] for r in b.values()),
        "flips": flips,
        "changed": changed,
        "simulated_a": sum(a[k]["simulated_time"] for k in common),
        "simulated_b": sum(b[k]["simulated_time"] for k in common),
    }


def counts(counter):
    return ", ".join(f"{name} {n}" for name, n in sorted(counter.items(), key=lambda x: -x[1]))


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("a", help="the first trials.csv")
    parser.add_argument("b", help="the second trials.csv")
    parser.add_argument("--list", type=int, default=0, metavar="N",
                        help="also list the first N trials whose verdicts differ")
    args = parser.parse_args(argv)
    if args.list < 0:
        parser.error("--list must be >= 0")
    try:
        a, b = load(args.a), load(args.b)
    except BadFile as e:
        print(f"compare-trials: {e}", file=sys.stderr)
        return 1
    r = compare(a, b)
    print(f"trials in both: {r['common']} (only in A: {r['only_a']}, only in B: {r['only_b']})")
    print(f"A: {counts(r['outcomes_a'])}")
    print(f"B: {counts(r['outcomes_b'])}")
    total = sum(r["flips"].values())
    print(f"verdicts that differ: {total}" + (
        " (" + ", ".join(f"{x} -> {y} {n}" for (x, y), n in r["flips"].most_common()) + ")"
        if total else ""))
    for key, (x, y) in r["changed"][:args.list]:
        print(f"  {'/'.join(key)}: {x} -> {y}")
    print(f"simulated time: A {r['simulated_a']:.1f} s, B {r['simulated_b']:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
