#!/usr/bin/env python3
"""The installed tree works without the source tree (CTest install_package, label install).

Installs the build into a temporary prefix, checks the layout (libraries, headers, data, schemas,
CMake package), configures and builds tests/install/consumer against the prefix with
find_package(VisGraB), runs it (one grasp trial of the installed SDH hand around a box: the
centred cylinder grasp that tests/rwsim/simulator holds stable), and runs the installed `visgrab`
from a temporary folder with no VISGRAB_DATA: its default data folder is the installed
share/visgrab/scenes: it generates one database scene from the installed objects and runs a
grasp in it with the installed SDH description. When the Python module is built
(VISGRAB_BUILD_PYTHON), it is imported from the prefix's Python folder
(VISGRAB_PYTHON_INSTALL_DIR, Debian's lib/python3/dist-packages) in the temporary folder:
Hand("sdh") is the installed description, and one grasp runs in that scene.
Exit 77 (skipped) when something it needs is missing: the built program, the CMake generator,
the compiler, or in a sanitizer build (the outside project would need the same instrumentation).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

SKIP = 77


def run(cmd, cwd=None, env=None):
    """Runs cmd; on failure prints its output and exits 1."""
    result = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    if result.returncode != 0:
        print(f"FAILED (exit {result.returncode}): {' '.join(cmd)}")
        print(result.stdout)
        print(result.stderr)
        sys.exit(1)
    return result.stdout


def check(condition, message):
    if not condition:
        print(f"FAILED: {message}")
        sys.exit(1)


def main():
    parser = argparse.ArgumentParser()
    for name in ("cmake", "generator", "cxx", "build", "consumer", "program", "instrumented",
                 "python", "python-module", "python-install-dir"):
        parser.add_argument(f"--{name}", required=True)
    args = parser.parse_args()

    built = args.program
    program_name = os.path.basename(built)
    if args.instrumented == "ON":
        print("SKIPPED: a VISGRAB_SANITIZE or VISGRAB_BUILD_FUZZERS build (the outside project is "
              "not built with the sanitizers its static libraries need)")
        return SKIP
    if not os.path.isfile(built):
        print(f"SKIPPED: {built} is not built (build everything before this test)")
        return SKIP
    if args.generator == "Ninja" and shutil.which("ninja") is None:
        print("SKIPPED: the consumer project needs ninja, which is not on PATH")
        return SKIP
    if not os.path.isfile(args.cxx):
        print(f"SKIPPED: no C++ compiler at {args.cxx}")
        return SKIP

    with tempfile.TemporaryDirectory(prefix="visgrab-install-") as tmp:
        tmp = os.path.realpath(tmp)
        prefix = os.path.join(tmp, "prefix")
        run([args.cmake, "--install", args.build, "--prefix", prefix])

        scenes = os.path.join(prefix, "share", "visgrab", "scenes")
        libdirs = [d for d in ("lib", "lib64") if os.path.isdir(os.path.join(prefix, d))]
        check(libdirs, f"no lib/ under {prefix}")
        lib = os.path.join(prefix, libdirs[0])
        for path in (
            os.path.join(prefix, "bin", program_name),
            os.path.join(lib, "librw_math.a"),
            os.path.join(lib, "librwsim_simulator.a"),
            os.path.join(lib, "libvisgrab_runner.a"),
            os.path.join(lib, "cmake", "VisGraB", "VisGraBConfig.cmake"),
            os.path.join(lib, "cmake", "VisGraB", "VisGraBConfigVersion.cmake"),
            os.path.join(lib, "cmake", "VisGraB", "VisGraBTargets.cmake"),
            os.path.join(prefix, "include", "visgrab", "rw", "math", "rpy.hpp"),
            os.path.join(prefix, "include", "visgrab", "rwsim", "simulator", "grasp_trial.hpp"),
            os.path.join(prefix, "include", "visgrab", "visgrab", "runner", "benchmark_runner.hpp"),
            os.path.join(scenes, "materials.xml"),
            os.path.join(scenes, "hands", "sdh", "sdh.grasp.xml"),
            os.path.join(scenes, "objects", "objects.xml"),
            os.path.join(prefix, "share", "visgrab", "xml", "workcell.xsd"),
        ):
            check(os.path.isfile(path), f"not installed: {os.path.relpath(path, prefix)}")

        # The outside project: configured with the prefix only, built and run in the temporary
        # folder.
        consumer_build = os.path.join(tmp, "consumer-build")
        run([args.cmake, "-S", args.consumer, "-B", consumer_build, "-G", args.generator,
             f"-DCMAKE_CXX_COMPILER={args.cxx}", "-DCMAKE_BUILD_TYPE=Release",
             f"-DCMAKE_PREFIX_PATH={prefix}"])
        run([args.cmake, "--build", consumer_build, "--config", "Release"])
        work = os.path.join(tmp, "work")
        os.mkdir(work)
        consumer = [path for path in (os.path.join(consumer_build, "consumer"),
                                      os.path.join(consumer_build, "Release", "consumer"))
                    if os.path.isfile(path)]
        check(consumer, f"no consumer program in {consumer_build}")
        out = run([consumer[0], scenes, work], cwd=work)
        print(f"consumer: {out.strip()}")
        words = out.split()
        check(len(words) == 6 and words[0] == "outcome" and words[2] == "contacts"
              and words[4] == "object", f"consumer printed {out!r}")
        check(words[1] == "stable", f"the centred cylinder grasp of the box is {words[1]}, "
              "not stable")
        check(int(words[3]) >= 3, f"{words[3]} contacts, expected the three fingers' at least")
        check(words[5] == "Box", f"the trial's object is {words[5]}, not Box")

        # The installed program, run from the temporary folder without VISGRAB_DATA: its default
        # data folder is the installed one (the help shows the default).
        program = os.path.join(prefix, "bin", program_name)
        env = {k: v for k, v in os.environ.items()
               if k not in ("VISGRAB_DATA", "VISGRAB_SOURCE_DIR")}
        helptext = run([program, "db", "generate", "--help"], cwd=work, env=env)
        check(f"--data DIR={scenes} " in helptext,
              f"`visgrab db generate --help` does not show the default data folder {scenes}:\n"
              + helptext)
        # One scene generated from the installed objects, then a grasp in it with the default
        # hand (the installed SDH's description): its cylinder pre-shape high above the table
        # closes on nothing, so the fingers reach the pre-shape's closed joint values.
        scene = "plain/single/amicelli/01"
        run([program, "db", "generate", "--out", "db", "--scenes", f"id={scene}", "--threads", "1",
             "--quiet"], cwd=work, env=env)
        check(os.path.isfile(os.path.join(work, "db", "scenes", scene, "left.png")),
              f"`visgrab db generate` made no {scene}/left.png")
        out = run([program, "grasp", "--db", "db", "--scene", scene, "--preshape", "SDH_CYL",
                   "--pose", "0", "0", "0.5", "0", "180", "0", "--json"], cwd=work, env=env)
        trial = json.loads(out)
        print(f"visgrab grasp: {trial['outcome']}, q grasp {trial['q_grasp']}")
        check(trial["hand"] == "SchunkHand", f"the default hand is {trial['hand']}, not the SDH")
        check(trial["outcome"] == "missed", f"a grasp 0.5 m above the table is {trial['outcome']}")
        closed = [0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349]  # SDH_CYL's qclose in sdh.grasp.xml
        check(len(trial["q_grasp"]) == 7
              and all(abs(a - b) < 0.01 for a, b in zip(trial["q_grasp"], closed)),
              f"q grasp {trial['q_grasp']}, expected SDH_CYL's closed values {closed}")

        if args.python_module == "ON":
            check_python_module(args, prefix, work, env, scene)
        else:
            print("the Python module is not built (VISGRAB_BUILD_PYTHON off): not checked")
        return 0


def check_python_module(args, prefix, work, env, scene):
    """The installed package, imported outside the source and build trees: its data folder and
    Hand("sdh") are the installed ones, and a grasp high above the table runs (missed)."""
    packages = os.path.join(prefix, args.python_install_dir)
    check(os.path.isfile(os.path.join(packages, "visgrab", "__init__.py")),
          f"the Python package is not installed in {packages}/visgrab")
    env = dict(env, PYTHONPATH=packages)
    script = f"""
import json, visgrab
hand = visgrab.Hand("sdh")
grasp = visgrab.Grasp.preshape(scene={scene!r}, method="installed", id="g1", preshape="SDH_CYL",
                               position=[0, 0, 0.5], quaternion=[0, 0, 1, 0])
trials = visgrab.run("db", [grasp], hand=hand, threads=1)
print(json.dumps(dict(module=visgrab.__file__, data=visgrab.data_folder(), hand=hand.file,
                      name=hand.name, outcome=trials[0].outcome)))
"""
    out = json.loads(run([args.python, "-c", script], cwd=work, env=env))
    print(f"installed Python module: {out}")
    scenes = os.path.join(prefix, "share", "visgrab", "scenes")
    check(out["module"].startswith(packages + os.sep), f"imported {out['module']}, not the "
          f"installed package under {packages}")
    check(out["data"] == scenes, f"visgrab.data_folder() is {out['data']}, not {scenes}")
    check(out["hand"] == os.path.join(scenes, "hands", "sdh", "sdh.grasp.xml"),
          f"Hand('sdh') is {out['hand']}, not the installed description")
    check(out["name"] == "SchunkHand", f"Hand('sdh') is {out['name']}")
    check(out["outcome"] == "missed", f"a grasp 0.5 m above the table is {out['outcome']}")


if __name__ == "__main__":
    sys.exit(main())
