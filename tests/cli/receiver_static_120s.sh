#!/usr/bin/env bash
# The receiver on a synthesized static 120 s scenario (8+ satellites at 45 dB-Hz):
# first fix within 40 s, horizontal RMS <= 3 m, vertical RMS <= 5 m, velocity RMS
# <= 0.05 m/s against the synthesizer's truth. Klobuchar parameters come from the
# navigation file until page 18 (every 12.5 min) is decoded.
#   usage: receiver_static_120s.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
sim_scenario "$src/data/scenarios/static_120s.yaml" "$work/sim"
run_on_sim "$work/sim" "$work/run" --iono-from "$brdc" --truth "$work/sim/truth.csv"
summary=$work/run/summary.json
check_json "satellites synthesized >= 8" "$work/sim/synthesis.json" 'len(satellites)' '>=' 8
check_json_each "$summary" \
  "time to first fix <= 40 s" time_to_first_fix_s '<=' 40.0 \
  "horizontal RMS <= 3 m" horizontal_error_m.rms '<=' 3.0 \
  "vertical RMS <= 5 m" vertical_error_m.rms '<=' 5.0 \
  "velocity RMS <= 0.05 m/s" velocity_error_mps.rms '<=' 0.05 \
  "a fix every epoch after the first 40" fixes '>=' $(($(json_value "$summary" epochs) - 40))
finish
