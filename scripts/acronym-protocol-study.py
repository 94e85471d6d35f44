#!/usr/bin/env python3
"""How the shake protocol's agreement with ACRONYM's FleX labels moves when each of its
parameters changes (docs/validation.md, "Agreement with ACRONYM's labels").

    scripts/acronym-protocol-study.py --acronym ../shared/acronym --out /tmp/study \
        [--visgrab build/apps/visgrab/visgrab] [--threads 2]

Makes the database and the grasp list once (`db from-acronym`, `import acronym`), then runs the
2,000 grasps with scenes/protocols/shake.xml and with one parameter of it changed at a time, and
prints one Markdown row per protocol: held share, agreement, kappa, user CPU seconds. Nothing is
fitted: each row changes one value of the documented protocol, except the last, which takes every
value of the public FleX grasping scene at once (docs/validation.md).
"""
import argparse
import csv
import pathlib
import re
import resource
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent.parent
TABLE = "Table_99cf659ae2fe4b87b72437fd995483b_0.009700376721042367.h5"

# (label, [(regex on shake.xml, replacement)]): one change each.
VARIANTS = [
    ("shake.xml as shipped", []),
    ("closing force 10 N", [(r'force="20"', 'force="10"')]),
    ("closing force 40 N", [(r'force="20"', 'force="40"')]),
    ("closing until rest", [(r'rule="force" force="20"', 'rule="rest"')]),
    ("translation 1 cm", [(r'amplitude="0.02"', 'amplitude="0.01"')]),
    ("translation 4 cm", [(r'amplitude="0.02"', 'amplitude="0.04"')]),
    ("translation at 2.5 Hz", [(r'frequency="5"', 'frequency="2.5"')]),
    ("rotation 7.5 deg", [(r'amplitude="0.2617993877991494"', 'amplitude="0.1308996938995747"')]),
    ("rotation 30 deg", [(r'amplitude="0.2617993877991494"', 'amplitude="0.5235987755982988"')]),
    ("no rotation phase", [(r'\s*<Shake motion="rotation"[^>]*/>', '')]),
    ("closing at most 0.2 m/s (franka_description's finger limit)",
     [(r'force="20"/>', 'force="20" speed="0.2"/>')]),
    ("closing at most 0.02 m/s (the FleX grasping scene's)",
     [(r'force="20"/>', 'force="20" speed="0.02"/>')]),
    # Not one change: every value of the public FleX grasping scene (docs/validation.md) at once.
    ("the FleX grasping scene's values, all at once",
     [(r'force="20"/>', 'force="20" speed="0.02"/>'),
      (r'amplitude="0.02" frequency="5"\s+cycles="2"',
       'amplitude="0.01" frequency="0.5" cycles="3"'),
      (r'amplitude="0.2617993877991494"\s+frequency="2" cycles="2" settle="0.1"',
       'amplitude="0.09817477042468103" frequency="0.5" cycles="3" settle="5"')]),
]


def run(args, command):
    done = subprocess.run([str(args.visgrab)] + command, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"visgrab {' '.join(command)} failed:\n{done.stdout}\n{done.stderr}")
    return done.stdout


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--acronym", type=pathlib.Path, required=True)
    parser.add_argument("--out", type=pathlib.Path, required=True)
    parser.add_argument("--visgrab", type=pathlib.Path,
                        default=HERE / "build/apps/visgrab/visgrab")
    parser.add_argument("--threads", default="2")
    args = parser.parse_args()
    h5 = args.acronym / "grasps" / TABLE
    args.out.mkdir(parents=True, exist_ok=True)
    db = args.out / "db"
    grasps = args.out / "grasps.csv"
    run(args, ["db", "from-acronym", str(h5), "--mesh-root", str(args.acronym), "--out", str(db),
               "--quiet"])
    run(args, ["import", "acronym", str(h5), "--db", str(db), "--out", str(grasps)])
    shake = (HERE / "scenes/protocols/shake.xml").read_text()
    print("| protocol | held (run) | agreement | kappa | user CPU s |")
    print("|---|---:|---:|---:|---:|")
    for i, (label, changes) in enumerate(VARIANTS):
        text = shake
        for pattern, replacement in changes:
            text, n = re.subn(pattern, replacement, text)
            if n == 0:
                sys.exit(f"{label}: {pattern} not found in shake.xml")
        protocol = args.out / f"protocol{i}.xml"
        protocol.write_text(text)
        results = args.out / f"results{i}"
        before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
        run(args, ["run", "--db", str(db), "--grasps", str(grasps), "--hand", "franka",
                   "--protocol", str(protocol), "--out", str(results), "--threads", args.threads,
                   "--quiet"])
        cpu = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - before
        agreement = args.out / f"agreement{i}"
        run(args, ["agreement", str(results), "--labels", str(h5), "--out", str(agreement)])
        with open(agreement / "label-agreement.csv") as f:
            row = next(r for r in csv.DictReader(f) if r["key"] == "all")
        print(f"| {label} | {100 * float(row['held_share_a']):.1f} % | "
              f"{100 * float(row['observed_agreement']):.1f} % | {float(row['kappa']):.3f} | "
              f"{cpu:.0f} |", flush=True)


if __name__ == "__main__":
    main()
