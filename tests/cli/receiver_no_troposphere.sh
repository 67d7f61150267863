#!/usr/bin/env bash
# IF synthesized without a troposphere (as gps-sdr-sim writes it), static, 30 s, assisted
# start: with --troposphere none the height is unbiased (vertical RMS <= 2 m), while the
# default Saastamoinen model applies delays the signal does not have and lifts the fix
# by metres. Unknown model names exit non-zero and list the accepted ones.
#   usage: receiver_no_troposphere.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
derive_scenario "$src/data/scenarios/static_120s.yaml" "$work/s.yaml" 'duration_s: 30' --append 'troposphere: false'
sim_scenario "$work/s.yaml" "$work/sim"
sim_source if_source "$work/sim"
assisted_run=("${if_source[@]}" "${assisted[@]}" --truth "$work/sim/truth.csv")
run_receiver "$work/none" "${assisted_run[@]}" --troposphere none
run_receiver "$work/default" "${assisted_run[@]}"
for unknown in "--troposphere hopfield saastamoinen" "--ionosphere nequick klobuchar"; do
  read -r option value accepted <<< "$unknown"
  expect_failure "$option $value" --ordered "unknown" "'$value'" "none" "$accepted" -- \
    "$deepnav" -q run "${assisted_run[@]}" --out "$work/bad" "$option" "$value"
done
check_json_each "$work/none/summary.json" "fixes with --troposphere none >= 15" fixes '>=' 15 \
  "vertical RMS with --troposphere none <= 2 m" vertical_error_m.rms '<=' 2.0
check_py "mean height error with --troposphere none within 1 m" -m checks.height_bias "$work/sim" "$work/none" 1.0
check_json "default model biases the height: vertical RMS >= 3 m" "$work/default/summary.json" vertical_error_m.rms '>=' 3.0
finish
