#!/usr/bin/env python3
"""Figure 7 of the paper: success rate against the number of attempts, one panel per group
(all scenes, then each condition), one line per method (the exact expectation) with the
randomized trials' estimate as dots (docs/report.md, "Success rate against attempts").

Usage: figure7.py INPUT OUT.png
  INPUT: a report folder of `visgrab analyze` (its attempts.csv) or one or more result folders
  of `visgrab run` (comma-separated; analysed first, without pictures, into a temporary folder).
Exit codes: 0 drawn, 1 bad input, 2 matplotlib is not installed (nothing drawn).
"""
import collections
import csv
import os
import sys
import tempfile


def read_attempts(path):
    """{group: {method: [(attempts, exact, randomized), ...]}} from attempts.csv."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    curves = collections.OrderedDict()
    for row in rows:
        number = lambda text: float(text) if text else float("nan")
        curves.setdefault(row["group"], collections.OrderedDict()).setdefault(
            row["method"], []).append((int(row["attempts"]), number(row["exact"]),
                                       number(row["randomized"])))
    return curves


def draw(curves, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    columns = min(3, len(curves))
    rows = (len(curves) + columns - 1) // columns
    figure, axes = plt.subplots(rows, columns, figsize=(4 * columns, 3.2 * rows), squeeze=False)
    for ax, (group, methods) in zip(axes.flat, curves.items()):
        for i, (method, points) in enumerate(methods.items()):
            n, exact, randomized = zip(*points)
            colour = f"C{i}"
            ax.plot(n, exact, color=colour, label=method)
            ax.plot(n, randomized, ".", color=colour)
        ax.set_title(group, fontsize=9)
        ax.set_xlabel("attempts")
        ax.set_ylabel("success rate")
        ax.set_ylim(0, 1)
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[len(curves):]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(out, dpi=120)


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 1
    source, out = argv[1], argv[2]
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("figure7.py: matplotlib is not installed (Debian: apt install python3-matplotlib); "
              "nothing drawn", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="figure7-") as tmp:
        attempts = os.path.join(source, "attempts.csv")
        if not os.path.isfile(attempts):
            import visgrab
            try:
                visgrab.analyze(source.split(","), out=tmp, pictures=False)
            except OSError as e:
                print(f"figure7.py: {e}", file=sys.stderr)
                return 1
            attempts = os.path.join(tmp, "attempts.csv")
        curves = read_attempts(attempts)
    if not curves:
        print(f"figure7.py: {attempts} holds no curve", file=sys.stderr)
        return 1
    draw(curves, out)
    print(f"Figure 7 ({len(curves)} groups) in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
