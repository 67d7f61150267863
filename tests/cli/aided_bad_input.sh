#!/usr/bin/env bash
# Bad input to the INS-aided modes: each gets a clear message and a non-zero exit, and
# no products pass for complete.
#   usage: aided_bad_input.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed -e 's/duration_s: 90/duration_s: 3/' "$src/data/scenarios/land_circle_aided_90s.yaml" > "$work/short.yaml"
"$deepnav" -q sim --scenario "$work/short.yaml" --out "$work/sim" > /dev/null || { echo "FAIL sim"; exit 1; }
head -n 102 "$work/sim/imu.csv" > "$work/imu_1s.csv"         # one second of a three-second run
sed -e '50s/,[^,]*$/,nan/' "$work/sim/imu.csv" > "$work/imu_nan.csv"
fail=0
expect_error() {  # name, expected message fragment, arguments...
  local name=$1 fragment=$2
  shift 2
  local out
  out=$("$deepnav" -q run --input "$work/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 \
        --out "$work/out_$name" --imu-grades-file "$src/data/imu_grades.yaml" "$@" 2>&1)
  local rc=$?
  if [ $rc -eq 0 ]; then echo "FAIL $name: exit 0"; fail=1; return; fi
  if ! grep -qi -- "$fragment" <<< "$out"; then echo "FAIL $name: message '$out' lacks '$fragment'"; fail=1; return; fi
  if [ -e "$work/out_$name/summary.json" ]; then echo "FAIL $name: summary.json written"; fail=1; return; fi
  echo "ok $name: $out"
}
expect_error no_imu "needs an IMU file" --mode ultra
expect_error short_imu "IMU log ends at" --mode tight --imu "$work/imu_1s.csv"
expect_error nan_imu "imu_nan.csv:50" --mode loose --imu "$work/imu_nan.csv"
expect_error bad_grade "foo" --mode ultra --imu "$work/sim/imu.csv" --imu-grade foo
expect_error bad_mode "deep" --mode deep --imu "$work/sim/imu.csv"
exit $fail
