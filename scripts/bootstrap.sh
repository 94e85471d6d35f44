#!/usr/bin/env bash
# VisGraB set-up on Debian 12: install the Debian packages, build, then either run the main job
# or run all tests.
#
#   scripts/bootstrap.sh run     install, build the `visgrab` program only (and the libraries it
#                                links) and run the main job: `visgrab benchmark` with the
#                                baseline method (database if absent, grasps, trials, report)
#   scripts/bootstrap.sh test    install, build (warnings as errors) and run every test, plus the
#                                malformed-input suites again under AddressSanitizer+UBSan, then
#                                the fuzz stage (scripts/fuzz.sh: every libFuzzer harness for a
#                                bounded time, clang build in build-fuzz; docs/fuzzing.md)
#
# Both commands configure the build directory alike, so `test` after `run` in the same clone
# builds only what `run` left out (tests, benchmarks, the viewer). The test builds keep CI fast
# (docs/performance.md, "CI time"): unity batches and the tests' precompiled header (both on by
# default), line-table debug info only (-g1), and in the sanitizer build just the targets the
# "sanitize"-labelled suites need.
#
# Environment: BUILD_DIR (default build), JOBS (default: number of cores), VISGRAB_DATABASE
# (the main job's scene database, generated there when absent, default database/),
# VISGRAB_RESULTS (the main job's output folder, default benchmark/; an interrupted run resumes),
# RW_COMPAT_DATA (RobWork's own files for the compatibility tests; they are skipped without it).
set -euo pipefail

mode=${1:-}
if [[ "$mode" != run && "$mode" != test ]]; then
  echo "usage: $0 run|test" >&2
  exit 2
fi

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$here"
build=${BUILD_DIR:-build}
jobs=${JOBS:-$(nproc)}

packages=(build-essential cmake ninja-build pkg-config
  libode-dev libeigen3-dev libxerces-c-dev libassimp-dev libopencv-dev
  qtbase5-dev libqhull-dev libgtest-dev libbenchmark-dev
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgl-dev
  libcli11-dev python3-jsonschema
  libhdf5-dev libzip-dev zlib1g-dev  # the grasp importers (VisGraB/visgrab/importers: HDF5 and its deflated chunks, .npz)
  pybind11-dev python3-dev python3-numpy  # the Python module (python/; docs/python.md)
  python3-pytest python3-pandas python3-matplotlib python3-pil  # its tests and examples (pandas: the result CSVs; Pillow: independent PNG decoding)
  slurm-wlm munge  # the Slurm cluster test starts its own one-node cluster (docs/cluster.md)
  xvfb xauth clang-format python3
  clang libclang-rt-14-dev  # the fuzz stage: clang 14 with libFuzzer and the sanitizer runtimes
  libmujoco-dev)  # MuJoCo 2.2.2: the optional second physics engine (rwsim_mujoco, its tests, dwc2mjcf, the MuJoCo comparison benchmark); built only when installed

install_packages() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]} == 0)); then
    echo "== all Debian packages present"
    return
  fi
  echo "== installing Debian packages: ${missing[*]}"
  local sudo=()
  [[ $(id -u) -eq 0 ]] || sudo=(sudo)
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# The main build's configuration, the same for both commands (`test` then completes `run`'s
# build instead of compiling everything again with other flags).
main_build_flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DVISGRAB_WERROR=ON -DVISGRAB_LINE_DEBUG_INFO=ON)

# configure_and_build DIR TARGET|all CMAKE_ARGS...
configure_and_build() {
  local dir=$1 target=$2
  shift 2
  echo "== configuring $dir"
  cmake -S . -B "$dir" -G Ninja "$@"
  echo "== building $target in $dir with $jobs jobs"
  cmake --build "$dir" --parallel "$jobs" --target "$target"
}

install_packages

if [[ "$mode" == run ]]; then
  # RelWithDebInfo (-O2), as the test build: one build serves both commands, and GCC 12's -O3
  # false-positive warnings stay out of the way. Only the program the main job runs.
  configure_and_build "$build" visgrab "${main_build_flags[@]}"
  db=${VISGRAB_DATABASE:-database}
  out=${VISGRAB_RESULTS:-benchmark}
  echo "== main job: visgrab benchmark, baseline method, database $db, output $out (resumable)"
  "$build/apps/visgrab/visgrab" benchmark --db "$db" --out "$out" --threads "$jobs" --resume
  echo "== report: $out/report/report.html (also report.md and the CSV tables there)"
  exit 0
fi

scripts/check-format.sh
configure_and_build "$build" all "${main_build_flags[@]}"
echo "== running all tests"
(cd "$build" && ctest --output-on-failure --parallel "$jobs")

echo "== malformed-input suites under AddressSanitizer+UBSan"
asan="${build}-asan"
cmake -S . -B "$asan" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DVISGRAB_SANITIZE=ON -DVISGRAB_WERROR=ON \
  -DVISGRAB_BUILD_BENCHMARKS=OFF -DVISGRAB_LINE_DEBUG_INFO=ON
cmake --build "$asan" --parallel "$jobs" --target sanitize_tests
(cd "$asan" && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --output-on-failure --parallel "$jobs" -L sanitize)

echo "== fuzz stage: libFuzzer harnesses (docs/fuzzing.md)"
BUILD_DIR="$build" JOBS="$jobs" scripts/fuzz.sh
