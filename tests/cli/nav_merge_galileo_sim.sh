#!/usr/bin/env bash
# `deepnav nav merge` rebuilds data/gps_galileo_20220101.rnx byte for byte and refuses bad
# input naming it; `deepnav sim --systems` adds Galileo satellites to a scenario, naming
# them E.. in sat_truth.csv, and refuses an unknown system or a file without Galileo.
#   usage: nav_merge_galileo_sim.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"

"$deepnav" nav merge --gps "$src/data/brdc0010.22n" --galileo "$src/data/galileo_20220220.rnx" \
  --galileo-week-shift -7 --out "$work/merged.rnx" > /dev/null
check "nav merge: the committed file, byte for byte" 'cmp -s "$work/merged.rnx" "$src/data/gps_galileo_20220101.rnx"'
check "nav merge: mixed file type" 'head -1 "$work/merged.rnx" | grep -q "M: MIXED"'

expect_failure merge_gps_as_galileo "brdc0010.22n" "no Galileo record" -- "$deepnav" nav merge \
  --gps "$src/data/brdc0010.22n" --galileo "$src/data/brdc0010.22n" --out "$work/x.rnx"
expect_failure merge_galileo_as_gps "galileo_20220220.rnx" "no GPS record" -- "$deepnav" nav merge \
  --gps "$src/data/galileo_20220220.rnx" --galileo "$src/data/galileo_20220220.rnx" --out "$work/y.rnx"
expect_failure merge_far_shift "--galileo-week-shift -5000" "before GST week 0" -- "$deepnav" nav merge \
  --gps "$src/data/brdc0010.22n" --galileo "$src/data/galileo_20220220.rnx" --galileo-week-shift -5000 \
  --out "$work/z.rnx"
check "nav merge: nothing written after a refusal" '[[ ! -e $work/x.rnx && ! -e $work/y.rnx && ! -e $work/z.rnx ]]'

scenario="$src/data/scenarios/static_gps_galileo_60s.yaml"
"$deepnav" sim --scenario "$scenario" --duration 0.05 --out "$work/mixed" > /dev/null
check "sim: Galileo rows in sat_truth.csv" 'grep -q "^0.000,E" "$work/mixed/sat_truth.csv"'
check "sim: GPS rows named G.." 'grep -q "^0.000,G" "$work/mixed/sat_truth.csv"'
check "sim: systems written back" 'grep -q "systems: \[gps, galileo\]" "$work/mixed/scenario.yaml"'
"$deepnav" sim --scenario "$scenario" --systems gps --duration 0.05 --out "$work/gps" > /dev/null
check "sim --systems gps: no Galileo row" '! grep -q ",E[0-9]" "$work/gps/sat_truth.csv"'
check "sim --systems gps: plain PRN column" 'grep -q "^0.000,[0-9]" "$work/gps/sat_truth.csv"'

expect_failure systems_unknown "--systems gps,glonass" "unknown system 'glonass'" -- "$deepnav" sim \
  --scenario "$scenario" --systems gps,glonass --duration 0.05 --out "$work/bad1"
printf '%s\n' 'start_time: "2022-01-01T20:30:00"' 'duration_s: 0.05' 'systems: [gps, galileo]' > "$work/no_gal.yaml"
expect_failure systems_without_records "brdc0010.22n" "no healthy E1-B I/NAV Galileo record" -- "$deepnav" sim \
  --scenario "$work/no_gal.yaml" --out "$work/bad2"
finish
