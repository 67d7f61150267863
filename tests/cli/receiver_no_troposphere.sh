#!/usr/bin/env bash
# IF synthesized without a troposphere (as gps-sdr-sim writes it), static, 30 s, assisted
# start: with --troposphere none the height is unbiased (vertical RMS <= 2 m), while the
# default Saastamoinen model applies delays the signal does not have and lifts the fix
# by metres. Unknown model names exit non-zero and list the accepted ones.
#   usage: receiver_no_troposphere.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed -e 's/duration_s: 120/duration_s: 30/' "$src/data/scenarios/static_120s.yaml" > "$work/s.yaml"
echo "troposphere: false" >> "$work/s.yaml"
"$deepnav" -q sim --scenario "$work/s.yaml" --out "$work/sim" > /dev/null || { echo "FAIL sim"; exit 1; }
run() {  # run OUT_DIR [extra options]
  local out=$1
  shift
  "$deepnav" -q run --input "$work/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 \
    --iono-from "$src/data/brdc0010.22n" --ephemeris-from "$src/data/brdc0010.22n" \
    --truth "$work/sim/truth.csv" --out "$out" "$@" > /dev/null
}
run "$work/none" --troposphere none || { echo "FAIL run --troposphere none"; exit 1; }
run "$work/default" || { echo "FAIL run (default troposphere)"; exit 1; }
failures=0
expect_unknown() {  # expect_unknown OPTION VALUE ACCEPTED_NAME
  local msg rc
  msg=$(run "$work/bad" "$1" "$2" 2>&1)
  rc=$?
  if [[ $rc -eq 0 || $msg != *"unknown"*"'$2'"*"none"*"$3"* ]]; then
    echo "FAIL $1 $2: exit $rc, message: $msg"; failures=$((failures + 1))
  else
    echo "ok   $1 $2: exit $rc, $(head -1 <<< "$msg")"
  fi
}
expect_unknown --troposphere hopfield saastamoinen
expect_unknown --ionosphere nequick klobuchar
python3 - "$work/none/summary.json" "$work/default/summary.json" "$work/none/pvt.csv" "$work/sim/truth.csv" <<'PY' || failures=$((failures + 1))
import csv, json, sys
none, default = (json.load(open(p)) for p in sys.argv[1:3])
# Signed height error of the --troposphere none run (the summary holds magnitudes only).
truth = {round(float(r["t_s"]), 3): float(r["height_m"]) for r in csv.DictReader(open(sys.argv[4]))}
dh = [float(r["height_m"]) - truth[round(float(r["t_s"]), 3)] for r in csv.DictReader(open(sys.argv[3]))
      if round(float(r["t_s"]), 3) in truth]
mean_dh = sum(dh) / len(dh) if dh else float("nan")
v_none, v_default = none["vertical_error_m"]["rms"], default["vertical_error_m"]["rms"]
checks = [
    ("fixes with --troposphere none >= 15", none["fixes"] >= 15, none["fixes"]),
    ("vertical RMS with --troposphere none <= 2 m", v_none <= 2.0, v_none),
    ("mean height error with --troposphere none within 1 m", abs(mean_dh) <= 1.0, mean_dh),
    ("default model biases the height: vertical RMS >= 3 m", v_default >= 3.0, v_default),
]
bad = 0
for name, ok, value in checks:
    print(("ok  " if ok else "FAIL"), name, value)
    bad += not ok
sys.exit(1 if bad else 0)
PY
exit $((failures > 0))
