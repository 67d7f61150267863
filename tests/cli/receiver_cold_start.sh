#!/usr/bin/env bash
# Cold start, nothing thrown away: a static scenario started 0, 3, 9, 15, 21 and 27 s after a
# subframe 1 boundary (data/scenarios/ttff_static_40s.yaml, 2.6 Msps ibyte). The ephemerides
# need subframe 1's clock words 7-10 and words 3-10 of subframes 2 and 3; each is taken from
# the first copy received whole, including the subframe under way at the start. So the
# fourth satellite's ephemeris is complete when the last of those words first ends after the
# start (`data_end`, seconds after the start in the satellites' time) plus the signal's
# travel time (67-90 ms here), and the first fix is the next 1 Hz epoch.
#   usage: receiver_cold_start.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
base=$src/data/scenarios/ttff_static_40s.yaml
# offset (s after the frame start) and data_end for it: at 0 and 3 subframe 3 ends last
# (18 s into the frame); at 9 the next frame's subframe 2 words 3-5 (they end 39 s into the
# first frame), at 15 its subframe 3 words 3-5 (45 s); at 21 and 27 its subframe 3 (48 s).
for case in "0 18.0" "3 15.0" "9 30.0" "15 30.0" "21 27.0" "27 21.0"; do
  read -r offset data_end <<< "$case"
  derive_scenario "$base" "$work/offset$offset.yaml" "start_time: \"2022-01-01T02:00:$(printf %02d "$offset")\""
  duration=$(awk -v e="$data_end" 'BEGIN { print int(e) + 3 }')
  sim_scenario "$work/offset$offset.yaml" "$work/sim$offset" --duration "$duration"
  run_on_sim "$work/sim$offset" "$work/run$offset"
  earliest=$(awk -v e="$data_end" 'BEGIN { print e + 0.06 }')
  latest=$(awk -v e="$data_end" 'BEGIN { print e + 0.10 }')
  epoch=$(awk -v e="$latest" 'BEGIN { print int(e) + 1 }')
  check_json_each "$work/run$offset/summary.json" \
    "offset $offset s: ephemerides complete no earlier than the data allow" first_fix.ephemerides_complete_s '>=' "$earliest" \
    "offset $offset s: ephemerides complete as the last word needed ends" first_fix.ephemerides_complete_s '<=' "$latest" \
    "offset $offset s: first fix at the next epoch" time_to_first_fix_s '<=' "$epoch" \
    "offset $offset s: a cold start" first_fix.method '==' cold
  check "offset $offset s: the run's closing line names the method" \
    "grep -q 'first fix at [0-9.]* s (cold; ephemerides of four satellites at' '$work/run$offset.log'"
done
finish
