#!/usr/bin/env bash
# The fuzz stage (docs/fuzzing.md): builds the libFuzzer harnesses of fuzz/ with clang in their own
# build folder, replays the kept reproducers (fuzz/regressions), then runs every harness for a
# bounded time on a corpus seeded from the project's own files. Any crash, hang, leak, sanitizer
# report or uncaught exception fails the stage (exit 1); the input is kept in the artifacts folder.
#
#   scripts/fuzz.sh [HARNESS...]     all harnesses (default) or the ones named (e.g. workcell png)
#
# Environment:
#   FUZZ_BUILD_DIR   build folder (default ${BUILD_DIR:-build}-fuzz)
#   FUZZ_SECONDS     run time per harness in seconds (default 10)
#   FUZZ_SHORT_SECONDS  run time of the grasp importers' readers (npy, npz, hdf5, json; default 5:
#                    small formats that saturate fast, and CI's time budget is close to its limit)
#   FUZZ_TIMEOUT     seconds one input may take before it counts as a hang (default 10)
#   FUZZ_RSS_MB      memory limit in MB, also the largest single allocation (default 2048)
#   FUZZ_JOBS        harnesses run side by side (default: JOBS or the number of cores)
#   FUZZ_DB          a generated scene database to seed index, calibration, workcell, mesh and
#                    image corpora from (default: the test stage's $BUILD_DIR/tests/test-database;
#                    without it, one scene is generated with VISGRAB_BIN, default
#                    $BUILD_DIR/apps/visgrab/visgrab, if built; else that part is skipped)
#   FUZZ_KEEP_CORPUS 1: keep and grow FUZZ_BUILD_DIR/corpus between runs (default: fresh each run)
#   FUZZ_FORK        1: long campaigns: libFuzzer's fork mode, which goes on after a finding and
#                    collects every one (the stage still fails if there was any)
#   FUZZ_SKIP_BUILD  1: use the harnesses already built in FUZZ_BUILD_DIR
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$here"
build=${FUZZ_BUILD_DIR:-${BUILD_DIR:-build}-fuzz}
seconds=${FUZZ_SECONDS:-10}
short_seconds=${FUZZ_SHORT_SECONDS:-5}
timeout=${FUZZ_TIMEOUT:-10}
rss_mb=${FUZZ_RSS_MB:-2048}
jobs=${FUZZ_JOBS:-${JOBS:-$(nproc)}}

all=(workcell dynamic_workcell rwtask experiment_xml grasp_list grasp_description object_spec
  calibration database_index original_manifest mesh png npy npz hdf5 json)
short=(npy npz hdf5 json)
if (($# > 0)); then harnesses=("$@"); else harnesses=("${all[@]}"); fi

start=$(date +%s)
if [[ ${FUZZ_SKIP_BUILD:-0} != 1 ]]; then
echo "== fuzz build in $build (clang, libFuzzer, ASan+UBSan)"
# Debug (assertions on) at -O1 with line tables: fast to build, fast enough to fuzz.
cmake -S . -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS_DEBUG="-O1 -gline-tables-only" \
  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -gline-tables-only" -DVISGRAB_BUILD_FUZZERS=ON \
  -DVISGRAB_BUILD_TESTS=OFF -DVISGRAB_BUILD_BENCHMARKS=OFF -DVISGRAB_BUILD_VIEWER=OFF >/dev/null
targets=()
for h in "${harnesses[@]}"; do targets+=("${h}_fuzzer"); done
cmake --build "$build" --parallel "$jobs" --target "${targets[@]}"
echo "== fuzz build done in $(($(date +%s) - start)) s"
fi

# --- seed corpora: copied from the project's files at run time (fuzz/seeds holds only inputs
# that exist nowhere else in the repository) ---
seeds="$build/seeds"
rm -rf "$seeds"
for h in "${all[@]}"; do
  mkdir -p "$seeds/$h"
  if [[ -d fuzz/seeds/$h ]]; then cp fuzz/seeds/$h/* "$seeds/$h/" 2>/dev/null || true; fi
done
copy_to() {  # copy_to HARNESS FILE...: each file under a name unique in the corpus
  local h=$1
  shift
  local f
  for f in "$@"; do
    [[ -f $f ]] || continue
    cp "$f" "$seeds/$h/$(echo "$f" | tr '/' '_')"
  done
}
copy_to workcell scenes/hands/*/*.wc.xml scenes/hands/*/*.prox.xml tests/rwsim/simulator/data/*.wc.xml \
  benchmarks/data/*.wc.xml
copy_to dynamic_workcell scenes/hands/*/*.dwc.xml scenes/materials.xml tests/rwsim/simulator/data/*.dwc.xml
copy_to grasp_description scenes/hands/*/*.grasp.xml
copy_to object_spec scenes/objects/objects.xml
# NPY and NPZ seeds written by numpy itself (python3-numpy): the dtypes, orders and versions the
# reader takes, an object array it refuses, a Contact-GraspNet-like npz. HDF5 seeds are committed
# (fuzz/seeds/hdf5: small ACRONYM-like files; no HDF5 writer is needed at fuzz time).
# Debian's python3 has python3-numpy; a python3 earlier in PATH (pyenv, a virtualenv) may not.
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
if "$py" -c "import numpy" 2>/dev/null; then
  "$py" - "$seeds" <<'PY'
import sys, numpy as np
out = sys.argv[1]
np.save(f"{out}/npy/f8.npy", np.arange(34, dtype="<f8").reshape(2, 17))
np.save(f"{out}/npy/f4_fortran.npy", np.asfortranarray(np.arange(6, dtype="<f4").reshape(2, 3)))
np.save(f"{out}/npy/be_i4.npy", np.arange(4, dtype=">i4"))
np.save(f"{out}/npy/b1.npy", np.array([True, False]))
np.save(f"{out}/npy/scalar.npy", np.float64(1.5))
np.save(f"{out}/npy/object.npy", np.array([{"a": 1}], dtype=object), allow_pickle=True)
g = np.tile(np.eye(4), (2, 1, 1))
np.savez(f"{out}/npz/plain.npz", grasps=g, scores=np.array([0.5, 0.25]))
np.savez_compressed(f"{out}/npz/deflated.npz", grasps=g, scores=np.array([0.5, 0.25]),
                    widths=np.array([0.04, 0.05]), segments=np.array([1, 1]))
np.savez(f"{out}/npz/pickled.npz", pred_grasps_cam={1: g}, scores={1: np.array([0.5, 0.25])})
PY
else
  echo "== no numpy: the npy and npz corpora are empty"
fi

db=${FUZZ_DB:-}
# The test suites' shared database (tests/support/test_database.hpp), made by the test stage.
test_db=${BUILD_DIR:-build}/tests/test-database
if [[ -z $db && -f $test_db/index.xml ]]; then db=$test_db; fi
if [[ -z $db ]]; then
  bin=${VISGRAB_BIN:-${BUILD_DIR:-build}/apps/visgrab/visgrab}
  if [[ -x $bin ]]; then
    db="$build/seed-db"
    if [[ ! -f $db/index.xml ]]; then
      echo "== generating one scene with $bin for the seed corpora"
      "$bin" db generate --out "$db" --scenes textured/single/cocacola/03 --threads 1 --quiet
    fi
  else
    echo "== no FUZZ_DB and no $bin: index, calibration and image seeds are the committed ones only"
  fi
fi
if [[ -n $db && -f $db/index.xml ]]; then
  copy_to database_index "$db/index.xml"
  scene_dir=$(dirname "$(find "$db/scenes" -name calibration.yml | sort | head -n 1)")
  copy_to calibration "$scene_dir/calibration.yml"
  copy_to workcell "$scene_dir/scene.wc.xml" "$db"/objects/*/*.wc.xml
  copy_to dynamic_workcell "$scene_dir/scene.dwc.xml" "$db"/objects/*/*.dwc.xml
  # Meshes: the first byte picks the extension (fuzz/mesh_fuzzer.cpp; 1 = .obj).
  for obj in "$db"/tables/*/*.obj; do
    { printf '\001'; cat "$obj"; } >"$seeds/mesh/$(basename "$obj")"
  done
  # Images: the smallest textures (the stereo pairs are large and slow to mutate).
  while read -r png; do copy_to png "$png"; done < <(find "$db" -name '*.png' -size -24k | sort | head -n 4)
fi

# --- run ---
artifacts="$build/artifacts"
mkdir -p "$artifacts" "$build/logs"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# Leaks inside Debian's assimp on malformed meshes are third-party (fuzz/lsan.supp says why).
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$here/fuzz/lsan.supp}

run_one() {
  local h=$1
  local bin="$build/fuzz/${h}_fuzzer"
  local corpus="$build/corpus/$h"
  local log="$build/logs/$h.log"
  [[ ${FUZZ_KEEP_CORPUS:-0} == 1 ]] || rm -rf "$corpus"
  mkdir -p "$corpus"
  local opts=(-timeout="$timeout" -rss_limit_mb="$rss_mb" -malloc_limit_mb="$rss_mb"
    -artifact_prefix="$artifacts/$h-" -print_final_stats=1)
  [[ -f fuzz/dicts/$h.dict ]] && opts+=(-dict="fuzz/dicts/$h.dict")
  # The kept reproducers first: each must now run cleanly.
  local regressions=()
  if [[ -d fuzz/regressions/$h ]]; then
    mapfile -t regressions < <(find "fuzz/regressions/$h" -type f | sort)
  fi
  if ((${#regressions[@]} > 0)) && ! "$bin" "${opts[@]}" "${regressions[@]}" >"$log" 2>&1; then
    echo "FAIL $h: a kept reproducer (fuzz/regressions/$h) fails again; see $log"
    return 1
  fi
  local run_time=$seconds
  [[ " ${short[*]} " == *" $h "* ]] && ((short_seconds < seconds)) && run_time=$short_seconds
  local run_opts=(-max_total_time="$run_time")
  if [[ ${FUZZ_FORK:-0} == 1 ]]; then
    run_opts+=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  fi
  local before after
  before=$(find "$artifacts" -name "$h-*" | wc -l)
  local ok=1
  "$bin" "${opts[@]}" "${run_opts[@]}" "$corpus" "$seeds/$h" >>"$log" 2>&1 || ok=0
  after=$(find "$artifacts" -name "$h-*" | wc -l)
  ((after == before)) || ok=0
  if ((ok == 0)); then
    echo "FAIL $h: $((after - before)) finding(s) in $artifacts/$h-* (see $log):"
    grep -E "ERROR: |runtime error|==ERROR|SUMMARY|uncaught|deadly signal|Test unit written" "$log" |
      head -n 8 | sed 's/^/    /'
    return 1
  fi
  local execs
  execs=$(grep -oE "^#[0-9]+" "$log" | tail -n 1 | tr -d '#')
  echo "ok   $h: ${execs:-?} runs in ${run_time} s, corpus $(find "$corpus" -type f | wc -l) files"
}

echo "== running ${#harnesses[@]} harnesses, $seconds s each, $jobs at a time (-timeout=$timeout" \
  "-rss_limit_mb=$rss_mb)"
status_dir=$(mktemp -d)
trap 'rm -rf "$status_dir"' EXIT
running=0
for h in "${harnesses[@]}"; do
  (run_one "$h" && touch "$status_dir/$h.ok") &
  running=$((running + 1))
  if ((running >= jobs)); then
    wait -n || true
    running=$((running - 1))
  fi
done
wait || true

failed=()
for h in "${harnesses[@]}"; do [[ -f $status_dir/$h.ok ]] || failed+=("$h"); done
echo "== fuzz stage done in $(($(date +%s) - start)) s"
if ((${#failed[@]} > 0)); then
  echo "fuzz stage FAILED: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz stage passed: ${#harnesses[@]} harnesses"
