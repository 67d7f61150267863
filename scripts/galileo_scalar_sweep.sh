#!/usr/bin/env bash
# Scalar fixes from GPS alone, Galileo alone and GPS+Galileo on the same synthesized IF: the
# mixed scenarios (Seoul: 9 GPS and 4 Galileo satellites; Helsinki: 7 and 8; static and land
# circle) over seeds 1..N. Each point synthesizes one scenario with one seed (45 s), runs the
# receiver three times on its samples (--systems gps, galileo, gps,galileo; assisted with the
# scenario's navigation file, so each fixes from the first time mark on) and writes
# OUT/points/SCENARIO_sSEED.json; a point whose file exists is skipped, so a sweep resumes
# where it stopped and its points can be handed to GNU parallel or a Slurm array.
#   usage: scripts/galileo_scalar_sweep.sh DEEPNAV OUT list [--seeds N]   the points, one per line
#          scripts/galileo_scalar_sweep.sh DEEPNAV OUT point SCENARIO SEED
#          scripts/galileo_scalar_sweep.sh DEEPNAV OUT all [--seeds N]    every point, in turn
#   e.g.   scripts/galileo_scalar_sweep.sh build/tools/deepnav results/galileo_scalar list |
#            parallel -j2 --colsep ' ' scripts/galileo_scalar_sweep.sh build/tools/deepnav results/galileo_scalar point {1} {2}
#          python3 scripts/galileo_scalar_report.py results/galileo_scalar   (table and plot)
set -euo pipefail
deepnav=$1
out=$2
action=$3
shift 3
src=$(cd "$(dirname "$0")/.." && pwd)
scenarios=(static_gps_galileo_60s land_circle_gps_galileo_60s static_gps_galileo_helsinki_60s
  land_circle_gps_galileo_helsinki_60s)
duration_s=45

points() {
  local seeds=10
  if [[ ${1:-} == --seeds ]]; then seeds=$2; fi
  for scenario in "${scenarios[@]}"; do
    for ((seed = 1; seed <= seeds; seed++)); do echo "$scenario $seed"; done
  done
}

point() {
  local scenario=$1 seed=$2
  local name="${scenario}_s${seed}" file="$src/data/scenarios/$scenario.yaml"
  local result="$out/points/$name.json"
  [[ -f $file ]] || { echo "galileo_scalar_sweep.sh: no scenario $file" >&2; exit 2; }
  [[ -e $result ]] && return 0
  local work
  work=$(mktemp -d "${TMPDIR:-/tmp}/galileo_scalar.XXXXXX")
  trap 'rm -rf "$work"' RETURN
  sed "s/^seed: .*/seed: $seed/" "$file" > "$work/scenario.yaml"
  (cd "$src" && "$deepnav" -q sim --scenario "$work/scenario.yaml" --duration "$duration_s" --out "$work/sim") \
    > "$work/sim.log" 2>&1 || { tail -5 "$work/sim.log" >&2; exit 1; }
  local nav
  nav=$(awk '/^nav_file:/ { print $2 }' "$file")
  for systems in gps galileo gps,galileo; do
    "$deepnav" -q run --metadata "$work/sim/if_ibyte.xml" --systems "$systems" --ephemeris-from "$src/$nav" \
      --truth "$work/sim/truth.csv" --out "$work/${systems/,/_}" > "$work/run.log" 2>&1 ||
      { tail -5 "$work/run.log" >&2; exit 1; }
  done
  mkdir -p "$out/points"
  /usr/bin/python3 - "$work" "$scenario" "$seed" > "$result.part" <<'PY'
import json, sys
work, scenario, seed = sys.argv[1], sys.argv[2], int(sys.argv[3])
point = {"scenario": scenario, "seed": seed, "runs": {}}
for systems in ("gps", "galileo", "gps_galileo"):
    s = json.load(open(f"{work}/{systems}/summary.json"))
    point["runs"][systems] = {
        "fixes": s["fixes"], "epochs": s["epochs"], "time_to_first_fix_s": s["time_to_first_fix_s"],
        "horizontal_rms_m": s["horizontal_error_m"]["rms"], "horizontal_p95_m": s["horizontal_error_m"]["p95"],
        "vertical_rms_m": s["vertical_error_m"]["rms"], "pdop_rms": s["pdop"]["rms"],
        "satellites_used_rms": s["satellites_used"]["rms"]}
json.dump(point, sys.stdout, indent=1)
PY
  mv "$result.part" "$result"
  echo "$name done" >&2
}

case $action in
  list) points "$@" ;;
  point) point "$@" ;;
  all) points "$@" | while read -r scenario seed; do point "$scenario" "$seed"; done ;;
  *) echo "galileo_scalar_sweep.sh: unknown action '$action' (expected list, point or all)" >&2; exit 2 ;;
esac
