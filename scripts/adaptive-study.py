#!/usr/bin/env python3
"""Adaptive repeats against fixed repeats: how far the per-grasp P and the robust figures move.

Usage: scripts/adaptive-study.py FIXED ADAPTIVE

FIXED and ADAPTIVE are result folders of `visgrab run --repeats N` and `visgrab run --repeats N
--adaptive` on the same grasps (same --seed). Reads their grasps.csv and prints, as Markdown:
  1. the trials each ran and, per method, the robust success rate (mean P over grasps) and the
     share of borderline grasps (0 < P < 1) of both;
  2. the share of grasps whose adaptive P lies inside the fixed run's 95 % Wilson interval
     (p_ci_low <= P <= p_ci_high), and how the others are spread;
  3. how many grasps the adaptive rule stopped early and how many of those the fixed run found
     borderline.
Python 3 standard library only.
"""

import csv
import sys
from collections import defaultdict


def read_grasps(folder):
    with open(f"{folder}/grasps.csv", newline="", encoding="utf-8") as f:
        return {(r["scene"], r["method"], r["grasp"]): r for r in csv.DictReader(f)}


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    fixed = read_grasps(sys.argv[1])
    adaptive = read_grasps(sys.argv[2])
    if set(fixed) != set(adaptive):
        sys.exit("the two runs hold other grasps")
    n = max(int(r["repeats"]) for r in fixed.values())
    trials = {name: sum(int(r["repeats"]) for r in run.values())
              for name, run in (("fixed", fixed), ("adaptive", adaptive))}
    print(f"{len(fixed)} grasps; trials: fixed {trials['fixed']}, adaptive {trials['adaptive']} "
          f"({trials['adaptive'] / len(fixed):.2f} per grasp, N = {n})\n")
    print("| method | grasps | robust rate fixed | robust rate adaptive | borderline fixed | "
          "borderline adaptive |")
    print("|---|---:|---:|---:|---:|---:|")
    by_method = defaultdict(list)
    for key in fixed:
        by_method[key[1]].append(key)
    for m in sorted(by_method):
        keys = by_method[m]

        def mean_p(run):
            return sum(float(run[k]["p"]) for k in keys) / len(keys)

        def borderline(run):
            return sum(0 < int(run[k]["held"]) < int(run[k]["repeats"]) for k in keys) / len(keys)

        print(f"| {m} | {len(keys)} | {mean_p(fixed):.3f} | {mean_p(adaptive):.3f} | "
              f"{borderline(fixed):.3f} | {borderline(adaptive):.3f} |")
    inside = 0
    outside = defaultdict(int)
    stopped = 0
    stopped_borderline = 0
    for key, f in fixed.items():
        a = adaptive[key]
        p = float(a["p"])
        if float(f["p_ci_low"]) <= p <= float(f["p_ci_high"]):
            inside += 1
        else:
            outside[f"fixed {f['held']}/{f['repeats']}, adaptive {a['held']}/{a['repeats']}"] += 1
        if int(a["repeats"]) < n:
            stopped += 1
            stopped_borderline += 0 < int(f["held"]) < int(f["repeats"])
    print(f"\nAdaptive P inside the fixed run's 95 % Wilson interval: {inside} of {len(fixed)} "
          f"grasps ({100 * inside / len(fixed):.1f} %).")
    print(f"Stopped early: {stopped} grasps; of those, {stopped_borderline} are borderline in the "
          f"fixed run ({100 * stopped_borderline / max(stopped, 1):.1f} %).")
    if outside:
        print("\nOutside, by counts:\n")
        for what, count in sorted(outside.items(), key=lambda x: -x[1])[:12]:
            print(f"- {what}: {count}")


if __name__ == "__main__":
    main()
