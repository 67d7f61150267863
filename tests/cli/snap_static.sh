#!/usr/bin/env bash
# `deepnav snap` on 2 s of the static scenario (fixed seed): 10 ms snapshots every 250 ms
# with a position hint, and one without it with the time hint a minute late, all within
# the error bounds; a time hint ten minutes off gives null entries and a reason (exit 5);
# a metadata file that dates the recording (<session><toa>) stands in for --time-hint, and
# without either the command says what is missing; bad input names the option or file; the
# real capture of another day (dated by its metadata) lists its satellites, then names the
# navigation file that is missing (exit 4).
#   usage: snap_static.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
derive_scenario "$src/data/scenarios/static_120s.yaml" "$work/static.yaml" 'duration_s: 2'
sim_scenario "$work/static.yaml" "$work/sim"
input=(--input "$work/sim/if_ibyte.bin" --fs "$(sample_rate_of "$work/sim")" --nav "$brdc")
start=2022-01-01T02:00:00

"$deepnav" snap "${input[@]}" --time-hint "$start" --position-hint 37.5,127.0,50 --every-ms 250 \
  --json "$work/hinted.json" --nmea "$work/hinted.nmea" --kml "$work/hinted.kml" > "$work/hinted.txt" ||
  abort "snap with a position hint failed"
check_py "10 ms snapshots with a position hint: median <= 15 m, all <= 40 m" -m checks.snap fixes \
  "$work/hinted.json" "$work/sim" --count 8 --median-m 15 --max-m 40
check "one NMEA GGA sentence per fix" '[[ $(grep -c "^\$GPGGA" "$work/hinted.nmea") -eq 8 ]]'
check "a KML track" 'grep -q "<kml" "$work/hinted.kml" && grep -q "127.0" "$work/hinted.kml"'
check "the table lists each snapshot" '[[ $(grep -c " good \| marginal " "$work/hinted.txt") -eq 8 ]]'

"$deepnav" snap "${input[@]}" --time-hint 2022-01-01T02:01:00 --start-ms 500 --json "$work/late.json" \
  > "$work/late.txt" || abort "snap without a position hint failed"
check_py "no position hint, time hint 60 s late: the fix and a -60 s correction" -m checks.snap fixes \
  "$work/late.json" "$work/sim" --median-m 40 --max-m 40 --time-correction-s -60

EXIT_STATUS=5 expect_failure "time hint 10 minutes off: no snapshot solved" "no snapshot solved" -- \
  "$deepnav" -q snap "${input[@]}" --time-hint 2022-01-01T02:10:00 --position-hint 37.5,127.0,50 \
  --json "$work/refused.json"
check_py "the refused snapshot: null coordinates, the time hint blamed" -m checks.snap refused \
  "$work/refused.json" "time hint"

# The sim's metadata with a session dated 18 s (the leap seconds) before 02:00:00 GPS.
sed 's#^  <lane id="IF">#  <session id="capture"><toa>2022-01-01T01:59:42Z</toa></session>\n&#' \
  "$work/sim/if_ibyte.xml" > "$work/sim/dated.xml"
"$deepnav" snap --metadata "$work/sim/dated.xml" --nav "$brdc" --position-hint 37.5,127.0,50 --every-ms 500 \
  --json "$work/dated.json" > "$work/dated.txt" 2> "$work/dated.log" || abort "snap dated by its metadata failed"
check_py "dated by the metadata's <session><toa>, no --time-hint: the fixes" -m checks.snap fixes \
  "$work/dated.json" "$work/sim" --count 4 --median-m 15 --max-m 40
check "the log names where the time hint came from" "grep -q 'from .*dated.xml.s <metadata/session\[capture\]/toa>' '$work/dated.log'"
expect_failure "no time hint at all" "no time hint" "--time-hint" "<session><toa>" -- \
  "$deepnav" snap "${input[@]}"
sed 's#<toa>2022-01-01T01:59:42Z</toa>#<toa>2022-01-01 noon</toa>#' "$work/sim/dated.xml" > "$work/sim/bad_date.xml"
expect_failure "an unreadable date in the metadata" "bad_date.xml" "<metadata/session[capture]/toa>" \
  "'2022-01-01 noon' is not a date and time" -- "$deepnav" snap --metadata "$work/sim/bad_date.xml" --nav "$brdc"

expect_failure "--length-ms 1" "--length-ms" -- "$deepnav" snap "${input[@]}" --time-hint "$start" --length-ms 1
expect_failure "malformed --time-hint" "--time-hint '2022-13-01T00:00:00'" "expected a date and time" -- \
  "$deepnav" snap "${input[@]}" --time-hint 2022-13-01T00:00:00
expect_failure "malformed --position-hint" "--position-hint '37.5,127'" "LAT,LON,H" -- \
  "$deepnav" snap "${input[@]}" --time-hint "$start" --position-hint 37.5,127
expect_failure "latitude out of range" "latitude '97.5'" -- \
  "$deepnav" snap "${input[@]}" --time-hint "$start" --position-hint 97.5,127,50
expect_failure "missing --nav file" "--nav" "$work/none.rnx" -- \
  "$deepnav" snap --input "$work/sim/if_ibyte.bin" --fs 2600000 --nav "$work/none.rnx" --time-hint "$start"
expect_failure "a snapshot past the end" "needs 26000 samples" -- \
  "$deepnav" snap "${input[@]}" --time-hint "$start" --start-ms 1995
expect_failure "overlapping snapshots" "--every-ms 5 is shorter than --length-ms 10" -- \
  "$deepnav" snap "${input[@]}" --time-hint "$start" --every-ms 5

capture=$src/data/L1_20211202_084700_4MHz_IQ.xml
EXIT_STATUS=4 expect_failure "real capture, navigation file of another day" --ordered "satellites found" "  31 " \
  "has no ephemeris valid at the time hint (2021-12-02" "broadcast ephemerides of 2021-12-02" "brdc3360.21n" -- \
  "$deepnav" -q snap --metadata "$capture" --nav "$brdc"
finish
