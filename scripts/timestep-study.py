#!/usr/bin/env python3
"""The time step's share of the error: one grasp list run at several ODE time steps, compared.

Usage: scripts/timestep-study.py RESULTS_5MS RESULTS_2.5MS RESULTS_1.25MS ... [--labels 5,2.5,...]

Each RESULTS is the folder of `visgrab run ... --dt DT` on the same database, grasp list and
scenes (the first is the reference, normally the default 5 ms). Prints, as Markdown:
  1. per method, the report's main figures at each step: the success rate (held grasps / grasps),
     the share of each outcome, p (scenes with a held grasp) and mean Q_lift of the held grasps;
  2. per step against the reference: the trials whose verdict (held / not held) flips, the
     trials whose outcome changes, and the change of each method's success rate, with a 95 %
     scene-bootstrap interval of that paired change (2,000 resamples, seed 1; the scene is the
     unit, as in the report), so the time-step error stands beside the statistical one.
Python 3 standard library only; the same input gives the same output.
"""

import argparse
import csv
import random
import sys
from collections import defaultdict

HELD = {"stable", "slipped"}
OUTCOMES = ["stable", "slipped", "dropped", "missed", "in_collision", "invalid_contacts",
            "simulation_failure", "timeout"]


def read_trials(folder):
    """{(scene, method, grasp): row} of FOLDER/trials.csv (repeat 0 only, if repeated)."""
    rows = {}
    with open(f"{folder}/trials.csv", newline="", encoding="utf-8") as f:
        for row in csv.DictReader(f):
            if row.get("repeat", "0") != "0":
                continue
            rows[(row["scene"], row["method"], row["grasp"])] = row
    return rows


def figures(rows, method):
    """The main figures of one method's trials."""
    mine = [r for r in rows.values() if r["method"] == method]
    held = [r for r in mine if r["outcome"] in HELD]
    scenes = defaultdict(bool)
    for r in mine:
        scenes[r["scene"]] |= r["outcome"] in HELD
    out = {"grasps": len(mine), "rate": len(held) / len(mine) if mine else float("nan"),
           "p": sum(scenes.values()) / len(scenes) if scenes else float("nan"),
           "q_lift": sum(float(r["q_lift"]) for r in held) / len(held) if held else float("nan")}
    for o in OUTCOMES:
        out[o] = sum(1 for r in mine if r["outcome"] == o) / len(mine) if mine else float("nan")
    return out


def paired_interval(ref, other, method, resamples=2000, seed=1):
    """95 % scene-bootstrap interval of the change of METHOD's success rate, OTHER - REF."""
    per_scene = defaultdict(lambda: [0, 0, 0])  # scene -> [grasps, held ref, held other]
    for key, r in ref.items():
        if r["method"] != method or key not in other:
            continue
        s = per_scene[r["scene"]]
        s[0] += 1
        s[1] += r["outcome"] in HELD
        s[2] += other[key]["outcome"] in HELD
    units = list(per_scene.values())
    rng = random.Random(seed)
    diffs = []
    for _ in range(resamples):
        g = a = b = 0
        for _ in range(len(units)):
            u = units[rng.randrange(len(units))]
            g += u[0]
            a += u[1]
            b += u[2]
        diffs.append((b - a) / g)
    diffs.sort()
    lo = diffs[int(0.025 * (resamples - 1))]
    hi = diffs[int(0.975 * (resamples - 1))]
    total = sum(u[0] for u in units)
    return (sum(u[2] for u in units) - sum(u[1] for u in units)) / total, lo, hi


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("results", nargs="+")
    parser.add_argument("--labels", help="comma-separated names of the runs (e.g. 5,2.5,1.25)")
    args = parser.parse_args()
    if len(args.results) < 2:
        sys.exit("give at least two result folders")
    labels = args.labels.split(",") if args.labels else args.results
    if len(labels) != len(args.results):
        sys.exit("--labels needs one name per result folder")
    runs = [read_trials(d) for d in args.results]
    ref = runs[0]
    for label, rows in zip(labels[1:], runs[1:]):
        if set(rows) != set(ref):
            sys.exit(f"run {label} holds other trials than run {labels[0]}")
    methods = sorted({r["method"] for r in ref.values()})
    print("| method | step | grasps | success rate | p | mean Q_lift | " +
          " | ".join(OUTCOMES[:5]) + " |")
    print("|---|---|---:|---:|---:|---:|" + "---:|" * 5)
    for m in methods:
        for label, rows in zip(labels, runs):
            f = figures(rows, m)
            print(f"| {m} | {label} | {f['grasps']} | {f['rate']:.3f} | {f['p']:.3f} | "
                  f"{f['q_lift']:.3f} | " + " | ".join(f"{f[o]:.3f}" for o in OUTCOMES[:5]) +
                  " |")
    print()
    simulated = [k for k, r in ref.items() if r["outcome"] not in ("in_collision",
                                                                   "invalid_contacts")]
    print(f"Against {labels[0]} ({len(ref)} trials, {len(simulated)} simulated at "
          f"{labels[0]}):\n")
    print("| step | held flips | outcome changes | " +
          " | ".join(f"{m}: rate change (95 % CI)" for m in methods) + " |")
    print("|---|---:|---:|" + "---:|" * len(methods))
    for label, rows in zip(labels[1:], runs[1:]):
        flips = sum(1 for k in ref if (ref[k]["outcome"] in HELD) != (rows[k]["outcome"] in HELD))
        changes = sum(1 for k in ref if ref[k]["outcome"] != rows[k]["outcome"])
        cells = []
        for m in methods:
            d, lo, hi = paired_interval(ref, rows, m)
            cells.append(f"{100 * d:+.1f} ({100 * lo:+.1f} to {100 * hi:+.1f}) points")
        print(f"| {label} | {flips} ({100 * flips / len(ref):.1f} %) | {changes} "
              f"({100 * changes / len(ref):.1f} %) | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
