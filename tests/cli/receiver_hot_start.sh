#!/usr/bin/env bash
# Hot start by coarse-time navigation: 20 s of the static scenario (fixed seed), the
# broadcast ephemerides given (--ephemeris-from) with --time-hint, fixes from the code
# phases before any HOW is decoded:
# - time hint 1.5 s off: the first fix by 2 s, made as coarse-time, its horizontal error
#   within twice the steady state's (the fixes from 10 s on); no fix wrong;
# - with --position-hint too: the first fix at the first epoch (1 s);
# - the ephemerides saved by one run (--save-ephemerides) start the next one hot;
# - without --time-hint, a metadata file's date of the recording (<file><timestamp>, UTC)
#   is the hint, and names the week;
# - time hint 60 s late, no position hint: a fix, or a refusal; never a wrong fix;
# - time hint 10 minutes off: refused, the time hint named, no coarse-time fix; the run
#   goes on as an assisted start;
# - bad options are named.
#   usage: receiver_hot_start.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
derive_scenario "$src/data/scenarios/static_120s.yaml" "$work/static.yaml" 'duration_s: 20'
sim_scenario "$work/static.yaml" "$work/sim"
hot=(--ephemeris-from "$brdc")

run_on_sim "$work/sim" "$work/near" "${hot[@]}" --time-hint 2022-01-01T02:00:01.5 \
  --save-ephemerides "$work/saved.rnx"
check_py "time hint 1.5 s off: first fix by 2 s as coarse-time, within twice the steady error, none wrong" \
  -m checks.receiver_hot_start "$work/near" "$work/sim" --first-fix-by 2
check_json_each "$work/near/summary.json" \
  "coarse-time fixes until the time of week is decoded" hot_start.fixes '>=' 1 \
  "the first time correction near -1.5 s (above)" hot_start.first_time_correction_s '>' -1.6 \
  "the first time correction near -1.5 s (below)" hot_start.first_time_correction_s '<' -1.4
check "the closing line names the method" "grep -q 'first fix at [0-9.]* s (coarse-time)' '$work/near.log'"
check "the saved ephemerides are a RINEX 3 navigation file" \
  "grep -q 'RINEX VERSION' '$work/saved.rnx' && [[ \$(grep -c '^G[0-9][0-9] ' '$work/saved.rnx') -ge 6 ]]"

run_on_sim "$work/sim" "$work/hinted" "${hot[@]}" --time-hint 2022-01-01T02:00:01.5 --position-hint 37.5,127.0,50
check_py "with a position hint: the first fix at the first epoch" \
  -m checks.receiver_hot_start "$work/hinted" "$work/sim" --first-fix-by 1

run_on_sim "$work/sim" "$work/saved" --ephemeris-from "$work/saved.rnx" --time-hint 2022-01-01T02:00:00
check_py "ephemerides saved by a run: a hot start from them" \
  -m checks.receiver_hot_start "$work/saved" "$work/sim" --first-fix-by 2

# The sim's metadata dated 1.5 s late in UTC (18 leap seconds behind GPS time).
sed 's#^    <url>\(.*\)</url>#&\n    <timestamp>2022-01-01T01:59:43.5Z</timestamp>#' "$work/sim/if_ibyte.xml" \
  > "$work/sim/dated.xml"
"$deepnav" run --metadata "$work/sim/dated.xml" --out "$work/dated" "${hot[@]}" > "$work/dated.log" 2>&1 ||
  abort "run dated by its metadata failed: $(tail -n 5 "$work/dated.log")"
check_py "the metadata's date as the time hint: first fix by 2 s as coarse-time" \
  -m checks.receiver_hot_start "$work/dated" "$work/sim" --first-fix-by 2
check_json_each "$work/dated/summary.json" \
  "its time correction near -1.5 s (above)" hot_start.first_time_correction_s '>' -1.6 \
  "its time correction near -1.5 s (below)" hot_start.first_time_correction_s '<' -1.4
check "the log names the metadata's timestamp" "grep -q 'time hint: 2022-01-01T01:59:43.500Z from .*dated.xml.s <metadata/file/timestamp>' '$work/dated.log'"

run_on_sim "$work/sim" "$work/late" "${hot[@]}" --time-hint 2022-01-01T02:01:00
check_json "time hint 60 s late, no position hint: a fix or a refusal" "$work/late/summary.json" \
  hot_start.attempts '>=' 1
check_py "time hint 60 s late: never a wrong fix" \
  -m checks.receiver_hot_start "$work/late" "$work/sim" --first-fix-by 2 --wrong-m 50

run_on_sim "$work/sim" "$work/far" "${hot[@]}" --time-hint 2022-01-01T02:10:00 --position-hint 37.5,127.0,50
check_json_each "$work/far/summary.json" \
  "time hint 10 minutes off: no coarse-time fix" hot_start.fixes '==' 0 \
  "the refusal names the time hint" hot_start.last_refusal contains '"time hint"' \
  "the first fix waits for the broadcast time" first_fix.method '==' '"ephemerides given"'
check_py "time hint 10 minutes off: never a wrong fix" \
  -m checks.receiver_hot_start "$work/far" "$work/sim" --first-fix-by 15 --method "ephemerides given"

input=$(ls "$work"/sim/if_*.bin)
expect_failure "--time-hint without --ephemeris-from" "--time-hint" "--ephemeris-from" -- \
  "$deepnav" run --input "$input" --fs 2600000 --out "$work/bad" --time-hint 2022-01-01T02:00:00
expect_failure "malformed --time-hint" "--time-hint '2022-01-01T25:00:00'" -- \
  "$deepnav" run --input "$input" --fs 2600000 --out "$work/bad" "${hot[@]}" --time-hint 2022-01-01T25:00:00
expect_failure "--save-ephemerides over the input" "--save-ephemerides" "would replace the input" -- \
  "$deepnav" run --input "$input" --fs 2600000 --out "$work/bad" --save-ephemerides "$input"
finish
