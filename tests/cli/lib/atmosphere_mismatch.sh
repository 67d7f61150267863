#!/usr/bin/env bash
# IF synthesized without one atmosphere delay (MODEL: troposphere or ionosphere), the
# receiver keeping its default models (Saastamoinen, Klobuchar), land circle with a
# tactical IMU, 90 s: tight and ultra-tight find the mismatch in the pseudorange
# residuals, take that model's state (summary.json MODEL_mismatch, a warning naming
# --MODEL none) and end no worse than loose coupling horizontally and well ahead
# vertically; --no-MODEL-mismatch keeps the 17-state filter (no state taken).
#   usage: atmosphere_mismatch.sh <deepnav binary> <source dir> troposphere|ionosphere
source "$(dirname "$0")/harness.sh" "$1" "$2"
model=${3:-}
[[ $model == troposphere || $model == ionosphere ]] ||
  { echo "atmosphere_mismatch.sh: model '$model' (expected troposphere or ionosphere)"; exit 2; }
sim_scenario "$src/data/scenarios/land_circle_aided_90s_no_$model.yaml" "$work/sim"
sim_imu imu "$work/sim"
aided=("${assisted[@]}" --truth "$work/sim/truth.csv" "${imu[@]}")
for mode in loose tight ultra; do run_on_sim "$work/sim" "$work/$mode" "${aided[@]}" --mode $mode; done
run_on_sim "$work/sim" "$work/ultra_off" "${aided[@]}" --mode ultra "--no-$model-mismatch"
for mode in tight ultra; do
  check "$mode: a warning naming --$model none" 'grep -q "$model none" "$work/$mode.log"'
done
check_py "the mismatch is found and the aided modes stay ahead of loose" -m checks.atmosphere_mismatch "$work" "$model"
finish
