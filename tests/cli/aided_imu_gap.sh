#!/usr/bin/env bash
# Four seconds of IMU data missing in ultra-tight mode: the run once said nothing, kept the
# label "ultra" and let the height drift to -319 m with no satellite. Now the gap is
# reported (log and summary.json), the INS stops across it (no solution labelled ultra or
# tight inside it) and restarts after it, and no published fix is far from the truth.
#   usage: aided_imu_gap.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
sim_scenario "$src/data/scenarios/land_circle_aided_90s.yaml" "$work/sim" --duration 25
sim_imu imu "$work/sim"
# The IMU log without 12 s < t < 16 s (the comment and header lines kept).
awk -F, '!($1 + 0 > 12.0 && $1 + 0 < 16.0) || $1 !~ /^[0-9.]+$/' "$work/sim/imu.csv" > "$work/imu_gap.csv"
imu[1]=$work/imu_gap.csv  # the file of sim_imu's --imu
run_on_sim "$work/sim" "$work/ultra" "${assisted[@]}" --truth "$work/sim/truth.csv" --mode ultra "${imu[@]}"
check "the gap is logged" \
  'grep -q "imu_gap.csv:[0-9]*: no IMU data from t = 1[12]\.[0-9]* s to 1[56]\.[0-9]* s" "$work/ultra.log"'
check_py "the gap is reported and bridged" -m checks.aided_imu_gap "$work/sim" "$work/ultra"
finish
