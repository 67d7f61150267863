#!/usr/bin/env bash
# Aided modes track on worker threads: the channels (and the filter's controllers of
# them) run in parallel within a block, and the filter reads them only between blocks in
# channel order, so every product is the same byte for byte for any --threads. Paper
# 003's land circle with a 30 s outage of every signal, so channels are taken over,
# coast, are lost, re-acquired and given back.
#   usage: aided_threads_identical.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
sim_scenario "$src/data/scenarios/land_circle_outage_120s.yaml" "$work/sim"
sim_imu imu "$work/sim"
for mode in ultra tight; do
  for threads in 1 2; do
    run_on_sim "$work/sim" "$work/$mode-$threads" --iono-from "$brdc" --truth "$work/sim/truth.csv" --mode $mode \
      "${imu[@]}" --threads $threads
  done
  check_same_products "$mode: --threads 1 and 2" "$work/$mode-1" "$work/$mode-2"
  check "$mode: the same log for --threads 1 and 2" 'cmp -s "$work/$mode-1.log" "$work/$mode-2.log"'
done
finish
