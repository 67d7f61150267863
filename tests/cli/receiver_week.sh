#!/usr/bin/env bash
# The GPS week of every product comes from the signal: the 2022-01-01 data run without
# --week (and without assistance) once came out dated the day of the run in pvt.csv, obs.rnx,
# NMEA and GPX while nav.rnx said 2022. The satellites broadcast the week modulo 1024; the
# build date resolves it, and every product must say 2022-01-01 (week 2190). A --week that
# contradicts the signal is an error naming it; a --week a week off (data across a week
# boundary) is not.
#   usage: receiver_week.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
# The bundled scenario from 3 s before a subframe 1 (sow 532800 is a multiple of 30 s) for
# 27 s: subframes 1-3, a whole ephemeris, are in by about 22 s.
derive_scenario "$src/data/scenarios/default.yaml" "$work/week.yaml" 'start_time: "2022-01-01T01:59:57"' \
  'duration_s: 27' "nav_file: $brdc"
sim_scenario "$work/week.yaml" "$work/sim"
week=$(week_of "$work/sim")
check "the scenario starts in week 2190" '[[ $week -eq 2190 ]]'
input=(--input "$work/sim/if_ibyte.bin" --fs "$(sample_rate_of "$work/sim")")
"$deepnav" run "${input[@]}" --out "$work/noweek" > "$work/noweek.txt" 2> "$work/noweek.err" ||
  abort "run without --week: $(cat "$work/noweek.err")"
check_py "no --week: every product dated 2022-01-01" -m checks.receiver_week "$work/noweek" "$week" 2022-01-01
check "the log names the week" 'grep -q "GPS week $week" "$work/noweek.err"'
# --week one off is a hint the signal settles; more is a contradiction, reported at once.
run_receiver "$work/week_after" "${input[@]}" --week $((week + 1))
expect_failure "--week $((week + 5)) refused" --ordered "--week $((week + 5)) contradicts the signal" \
  "week number $((week % 1024)) (modulo 1024), i.e. week $week" "give --week $week" -- \
  "$deepnav" -q run "${input[@]}" --week $((week + 5)) --out "$work/week_contradicting"
check "--week $((week + 1)) gives the same pvt.csv (but for the first column, t_s)" \
  'cmp -s <(cut -d, -f2- "$work/noweek/pvt.csv") <(cut -d, -f2- "$work/week_after/pvt.csv")'
finish
