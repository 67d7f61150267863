#!/usr/bin/env bash
# Filter-guided reacquisition (data/scenarios/land_circle_weak_rising_60s.yaml): PRN 25 is
# blocked for the first 20 s and then received at 20 dB-Hz, well below what the FFT
# acquisition finds. In ultra-tight mode the filter predicts where its signal is, a narrow
# search with seconds of integration finds it after it rises and not before, and the
# channel started there, its bits and time taken from the prediction, is steered and
# measured by the filter within 10 s of the signal's return (eight satellites in the
# filter); the solution stays within 1.5 m. With --no-guided-reacquisition the satellite is
# never tracked (seven satellites throughout).
#   usage: guided_reacquisition.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
sim_scenario "$src/data/scenarios/land_circle_weak_rising_60s.yaml" "$work/sim"
sim_imu imu "$work/sim"
aided=("${assisted[@]}" --truth "$work/sim/truth.csv" --mode ultra "${imu[@]}")
run_on_sim "$work/sim" "$work/guided" "${aided[@]}"
run_on_sim "$work/sim" "$work/unguided" "${aided[@]}" --no-guided-reacquisition
check_py "PRN 25 found by the filter's search once it rises" -m checks.guided_reacquisition "$work"
finish
