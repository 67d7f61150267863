#!/usr/bin/env bash
# The error world reaches the pseudoranges: the same static 30 s scenario synthesized in
# the `none` world (the receiver's own models are the truth) and in `suburban` (thin-shell
# ionosphere, site troposphere, broadcast orbit/clock errors, patch antenna, land-mobile
# multipath and blockage), run through the scalar receiver with its default models. The
# suburban run must show clearly larger position errors, and sat_truth.csv must carry the
# error budget (nonzero ionosphere residual, orbit and multipath columns; all zero in none).
#   usage: receiver_error_world.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
for world in none suburban; do
  derive_scenario "$src/data/scenarios/static_120s.yaml" "$work/$world.yaml" 'duration_s: 30' \
    --append "errors: {preset: $world}"
  sim_scenario "$work/$world.yaml" "$work/sim_$world"
  run_on_sim "$work/sim_$world" "$work/run_$world" "${assisted[@]}" --truth "$work/sim_$world/truth.csv"
done
check_py "the error budget reaches the fixes" -m checks.receiver_error_world "$work"
finish
