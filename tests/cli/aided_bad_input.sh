#!/usr/bin/env bash
# Bad input to the INS-aided modes: each gets a clear message and a non-zero exit, and
# no products pass for complete.
#   usage: aided_bad_input.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
sim_scenario "$src/data/scenarios/land_circle_aided_90s.yaml" "$work/sim" --duration 3
head -n 102 "$work/sim/imu.csv" > "$work/imu_1s.csv"  # one second (two header lines) of a three-second run
sed -e '50s/,[^,]*$/,nan/' "$work/sim/imu.csv" > "$work/imu_nan.csv"
sim_source if_source "$work/sim"
expect_run_error() {  # NAME FRAGMENT RUN_OPTIONS...: refused, naming FRAGMENT, no summary.json
  local name=$1 fragment=$2
  shift 2
  expect_failure "$name" "$fragment" -- "$deepnav" -q run "${if_source[@]}" --out "$work/out_$name" \
    --imu-grades-file "$imu_grades" "$@"
  if [[ $last_check == ok ]]; then check "$name: no summary.json written" '[[ ! -e $work/out_$name/summary.json ]]'; fi
}
expect_run_error no_imu "needs an IMU file" --mode ultra
expect_run_error short_imu "IMU log ends at" --mode tight --imu "$work/imu_1s.csv"
expect_run_error nan_imu "imu_nan.csv:50" --mode loose --imu "$work/imu_nan.csv"
expect_run_error bad_grade "foo" --mode ultra --imu "$work/sim/imu.csv" --imu-grade foo
expect_run_error bad_mode "deep" --mode deep --imu "$work/sim/imu.csv"
finish
