#!/usr/bin/env bash
# GPS week rollover: a scenario from 23 s before the end of GPS week 2190 (2022-01-01
# 23:59:37) to 11 s into week 2191. Each satellite broadcasts in subframe 1 the week that
# subframe is sent in, 2191 from the first one after the boundary (the simulator once kept
# its ephemeris's week, and `run` then dated the products a week early, or stopped with a
# contradiction whose advice named the very week given). Every run must date every fix and
# observation as the truth does: assisted (the ephemeris file's epoch dates the clock before
# any subframe 1), with --week naming either side or none, and unassisted (near a week
# boundary the clock waits for subframe 1, whatever --week says).
#   usage: receiver_week_rollover.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
derive_scenario "$src/data/scenarios/default.yaml" "$work/roll.yaml" 'start_time: "2022-01-01T23:59:37"' \
  'duration_s: 34' 'sample_rate_hz: 2048000' "nav_file: $brdc"
sim_scenario "$work/roll.yaml" "$work/sim"
start_week=$(week_of "$work/sim")
check "the scenario starts in week 2190" '[[ $start_week -eq 2190 ]]'
input=(--input "$work/sim/if_ibyte.bin" --fs 2048000)
run_receiver "$work/assisted" "${input[@]}" --ephemeris-from "$brdc"
check_py "assisted: fixes on both sides of the boundary, dated as the truth" \
  -m checks.receiver_week_rollover "$work/assisted" "$work/sim" --both-weeks
for week in 2190 2191; do
  run_receiver "$work/assisted_$week" "${input[@]}" --ephemeris-from "$brdc" --week $week
  check "assisted, --week $week: the same fixes" \
    'cmp -s <(cut -d, -f2- "$work/assisted/pvt.csv") <(cut -d, -f2- "$work/assisted_$week/pvt.csv")'
done
for week in none 2190 2191; do
  week_option=()
  [[ $week == none ]] || week_option=(--week $week)
  run_receiver "$work/plain_$week" "${input[@]}" "${week_option[@]}"
  check_py "unassisted, --week $week: observations dated as the truth" \
    -m checks.receiver_week_rollover "$work/plain_$week" "$work/sim"
done
finish
