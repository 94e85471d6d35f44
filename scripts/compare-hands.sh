#!/usr/bin/env bash
# One pre-shape grasp plan run with several hands, and one report comparing them
# (docs/adding-a-hand.md, step 5).
#
#   scripts/compare-hands.sh [OUT]
#
# The plan: the baseline's two-contact grasps on ten scenes as pre-shape grasps with the
# pre-shape "wide" (every two-finger hand of scenes/hands/ has it). Each hand runs it
# (OUT/<hand>), then `visgrab analyze` writes OUT/report/report.html with the hands side by side.
#
# Environment: VISGRAB (the binary, default build/apps/visgrab/visgrab), VISGRAB_DATABASE
# (default database/, generated there when absent), HANDS (default "sdh pg70 robotiq2f85
# franka", and robwork-robotiq when RW_COMPAT_DATA is set: folders of scenes/hands/ or paths),
# SCENES (a scene filter, default the ten scenes below), JOBS.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-hand-comparison}
visgrab=${VISGRAB:-$here/build/apps/visgrab/visgrab}
db=${VISGRAB_DATABASE:-database}
jobs=${JOBS:-$(nproc)}
# RobWork's own Robotiq model joins when its files are at hand (scenes/hands/robwork-robotiq).
default_hands="sdh pg70 robotiq2f85 franka"
[[ -n "${RW_COMPAT_DATA:-}" ]] && default_hands+=" robwork-robotiq"
hands=${HANDS:-$default_hands}
scenes=${SCENES:-"plain/single/cocacola/01;plain/single/saltbox/01;plain/single/marmelade/03;\
plain/single/peachcan/02;plain/single/greencup/04;textured/single/cocacola/02;\
textured/single/tomato/04;textured/single/corny/01;plain/double/cocacola_saltcylinder/01;\
textured/double/marmelade_pure/02"}

if [[ ! -f "$db/index.xml" ]]; then
  echo "== generating the ten scenes into $db"
  "$visgrab" db generate --out "$db" --scenes "$scenes" --threads "$jobs"
fi
mkdir -p "$out"
echo "== the plan: the baseline's two-contact grasps as pre-shape grasps (wide)"
"$visgrab" baseline --db "$db" --scenes "$scenes" --preshape wide --threads "$jobs" \
  --out "$out/plan.csv"
runs=()
for hand in $hands; do
  dir=$hand
  [[ -d "$dir" ]] || dir=$here/scenes/hands/$hand
  name=$(basename "$dir")
  echo "== $name"
  rm -rf "${out:?}/$name"
  "$visgrab" run --db "$db" --grasps "$out/plan.csv" --hand "$dir" --scenes "$scenes" \
    --threads "$jobs" --out "$out/$name" --quiet
  runs+=("$out/$name")
done
"$visgrab" analyze "${runs[@]}" --out "$out/report" --threads "$jobs"
echo "== report: $out/report/report.html"
