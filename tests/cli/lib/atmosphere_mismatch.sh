#!/usr/bin/env bash
# IF synthesized without one atmosphere delay (MODEL: troposphere or ionosphere) or without
# both (MODEL: atmosphere), the receiver keeping its default models (Saastamoinen,
# Klobuchar), land circle with a tactical IMU, 90 s: tight and ultra-tight find the
# mismatch in the pseudorange residuals (both: the troposphere's, then the ionosphere's
# fitted beside it), take the states (summary.json *_mismatch, warnings naming --* none)
# and end no worse than loose coupling horizontally and well ahead vertically; with the
# watches off (--no-*-mismatch) the 17-state filter takes no state.
#   usage: atmosphere_mismatch.sh <deepnav binary> <source dir> troposphere|ionosphere|atmosphere
source "$(dirname "$0")/harness.sh" "$1" "$2"
model=${3:-}
[[ $model == troposphere || $model == ionosphere || $model == atmosphere ]] ||
  { echo "atmosphere_mismatch.sh: model '$model' (expected troposphere, ionosphere or atmosphere: both)"; exit 2; }
sim_scenario "$src/data/scenarios/land_circle_aided_90s_no_$model.yaml" "$work/sim"
sim_imu imu "$work/sim"
aided=("${assisted[@]}" --truth "$work/sim/truth.csv" "${imu[@]}")
for mode in loose tight ultra; do run_on_sim "$work/sim" "$work/$mode" "${aided[@]}" --mode $mode; done
if [[ $model == atmosphere ]]; then
  run_on_sim "$work/sim" "$work/ultra_off" "${aided[@]}" --mode ultra --no-troposphere-mismatch --no-ionosphere-mismatch
else
  run_on_sim "$work/sim" "$work/ultra_off" "${aided[@]}" --mode ultra "--no-$model-mismatch"
fi
for mode in tight ultra; do
  for named in troposphere ionosphere; do
    [[ $model == "$named" || $model == atmosphere ]] || continue
    check "$mode: a warning naming --$named none" 'grep -q "$named none" "$work/$mode.log"'
  done
done
check_py "the mismatch is found and the aided modes stay ahead of loose" -m checks.atmosphere_mismatch "$work" "$model"
finish
