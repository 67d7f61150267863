#!/usr/bin/env bash
# Observables and fixes at 50 Hz (the fastest rate) with an assisted start: fixes every
# 20 ms once the clock is set, RINEX epochs at that interval, metre-level errors, and the
# summary's per-satellite navigation-data report; the same products with worker threads.
#   usage: receiver_50hz.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
sim_scenario "$src/data/scenarios/land_circle_60s.yaml" "$work/sim" --duration 20
run_on_sim "$work/sim" "$work/run" --rate 50 "${assisted[@]}" --truth "$work/sim/truth.csv"
# Worker threads split the channels of each block: the products must not change.
run_on_sim "$work/sim" "$work/run_threads" --rate 50 "${assisted[@]}" --threads 3
for f in pvt.csv obs.rnx tracking.csv; do
  check "$f the same with --threads 3" 'cmp -s "$work/run/$f" "$work/run_threads/$f"'
done
check_py "50 Hz products" -m checks.receiver_50hz "$work/run"
finish
