#!/usr/bin/env bash
# Aided modes track on worker threads: the channels (and the filter's controllers of
# them) run in parallel within a block, and the filter reads them only between blocks in
# channel order, so every product is the same byte for byte for any --threads. Paper
# 003's land circle with a 30 s outage of every signal, so channels are taken over,
# coast, are lost, re-acquired and given back.
#   usage: aided_threads_identical.sh <deepnav binary> <source dir>
set -uo pipefail
source "$(dirname "$0")/lib/same_products.sh"
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$deepnav" -q sim --scenario "$src/data/scenarios/land_circle_outage_120s.yaml" --out "$work/sim" > /dev/null || { echo "FAIL sim"; exit 1; }
status=0
for mode in ultra tight; do
  for threads in 1 2; do
    "$deepnav" -q run --input "$work/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 \
      --iono-from "$src/data/brdc0010.22n" --truth "$work/sim/truth.csv" --out "$work/$mode-$threads" \
      --mode $mode --imu "$work/sim/imu.csv" --imu-grade tactical --imu-lever-arm 0.8 -0.3 0.4 \
      --threads $threads > "$work/$mode-$threads.stdout" || { echo "FAIL run $mode --threads $threads"; exit 1; }
  done
  for f in "$work/$mode-1"/* "$work/$mode-1.stdout"; do
    other=${f/$mode-1/$mode-2}
    if ! same_product "$f" "$other"; then
      echo "FAIL $mode: $(basename "$f") differs between --threads 1 and --threads 2"
      status=1
    fi
  done
  [ $status -eq 0 ] && echo "ok: $mode: $(ls "$work/$mode-1" | wc -l) products identical for --threads 1 and 2"
done
exit $status
