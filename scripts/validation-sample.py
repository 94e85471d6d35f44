#!/usr/bin/env python3
"""A seeded sample of a run's simulated trials, as a grasp list to run on another engine.

Usage: scripts/validation-sample.py --results RESULTS --grasps GRASPS.csv --count N [--seed S]
                                    --out SAMPLE.csv

Reads RESULTS/trials.csv (a run of `visgrab run` on the grasp list GRASPS.csv), keeps the trials
that were simulated (every outcome but in_collision and invalid_contacts: those are decided before
any simulation and agree on every engine by construction), and draws N of them with the seed S
(default 1), stratified: every (table, single/double, object) cell with simulated trials gets
at least one, the rest are drawn in proportion to the cells' sizes (largest remainders). The
sampled grasps' lines of GRASPS.csv are written to SAMPLE.csv in their original order (comment
and blank lines dropped), so that `visgrab run --grasps SAMPLE.csv --engine mujoco` runs exactly
those trials and `visgrab agreement` pairs them with RESULTS. A summary per cell goes to stdout.
Python 3 standard library only; the same input and seed give the same file.
"""

import argparse
import csv
import random
import sys

DECIDED_BEFORE_SIMULATION = {"in_collision", "invalid_contacts"}


def cell_of(scene, obj):
    """(table, kind, object) of a trial: scene ids read texture/kind/..., e.g.
    plain/single/cocacola/03; the object is the trial's object column (the grasped one)."""
    parts = scene.split("/")
    if len(parts) < 2:
        raise ValueError(f"scene id {scene!r} is not texture/kind/...")
    return parts[0], parts[1], obj


def read_trials(path):
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        needed = {"scene", "method", "grasp", "outcome", "object"}
        if reader.fieldnames is None or not needed <= set(reader.fieldnames):
            raise ValueError(f"{path}: expected the columns {sorted(needed)} of trials.csv")
        return list(reader)


def allocate(cells, count):
    """Per cell how many to draw: one each, the rest by largest remainder of the cells' shares."""
    total = sum(len(v) for v in cells.values())
    keys = sorted(cells)
    if count < len(keys):
        raise ValueError(f"--count {count} is fewer than the {len(keys)} cells to cover")
    if count >= total:
        return {k: len(cells[k]) for k in keys}
    share = {k: 1 + (count - len(keys)) * (len(cells[k]) - 1) / (total - len(keys)) for k in keys}
    take = {k: min(len(cells[k]), int(share[k])) for k in keys}
    left = count - sum(take.values())
    for k in sorted(keys, key=lambda k: (-(share[k] - int(share[k])), k)):
        if left == 0:
            break
        if take[k] < len(cells[k]):
            take[k] += 1
            left -= 1
    return take


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", required=True)
    parser.add_argument("--grasps", required=True)
    parser.add_argument("--count", type=int, required=True)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv[1:])
    try:
        trials = read_trials(f"{args.results}/trials.csv")
        cells = {}
        for t in trials:
            if t["outcome"] in DECIDED_BEFORE_SIMULATION:
                continue
            cells.setdefault(cell_of(t["scene"], t["object"]), []).append(
                (t["scene"], t["method"], t["grasp"]))
        take = allocate(cells, args.count)
    except (OSError, ValueError) as e:
        sys.stderr.write(f"validation-sample: {e}\n")
        return 2
    rng = random.Random(args.seed)
    chosen = set()
    for k in sorted(cells):
        chosen.update(rng.sample(sorted(cells[k]), take[k]))
    written = 0
    with open(args.grasps, encoding="utf-8") as f, open(args.out, "w", encoding="utf-8") as out:
        for line in f:
            body = line.split("#", 1)[0].strip()
            if not body:
                continue
            fields = [x.strip() for x in body.split(",")]
            if len(fields) >= 3 and (fields[0], fields[1], fields[2]) in chosen:
                out.write(line if line.endswith("\n") else line + "\n")
                written += 1
    if written != len(chosen):
        sys.stderr.write(f"validation-sample: {len(chosen)} trials drawn but {written} of their "
                         f"grasps found in {args.grasps}: is it the run's grasp list?\n")
        return 1
    print(f"{written} of {sum(len(v) for v in cells.values())} simulated trials "
          f"({len(trials)} in all) in {len(cells)} cells, seed {args.seed}: {args.out}")
    for k in sorted(cells):
        print(f"  {k[0]:8s} {k[1]:6s} object {k[2]:>2s}: {take[k]:4d} of {len(cells[k])}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
