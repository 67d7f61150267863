#!/usr/bin/env bash
# deepnav fuse on recordings that fall short, each an edit of the real walk (data/walk_0827)
# made here by pylib/walk_edit.py: what the file says of itself is honoured (its time
# system, its events' new observation types), the data win over a header that disagrees,
# an epoch written twice is skipped; where the IMU log has no data the INS stops and only
# the single point is published, labelled so; an IMU log going back in time, an
# observation file without GPS, GLO tags without leap seconds and numeric options out of
# range are refused, naming the file and line or the option, with nothing written; no
# epoch scored is no statistic, not a perfect one.
#   usage: fuse_integrity.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
walk=$src/data/walk_0827
cd "$work"
edit() { py -m walk_edit "$@" || abort "walk_edit $*"; }
fuse() {  # fuse OUT [options]: the walk's configuration with those options; its log in OUT.log
  local out=$1
  shift
  "$deepnav" -q fuse --config "$walk/walk.yaml" --out "$out" "$@" > "$out.log" 2>&1 || abort "fuse $*: $(tail -n 5 "$out.log")"
}
fuse walk

# The observation file's own word: the same recording with its tags in BDT (14 s behind GPS
# time), a flag-4 event that swaps the first two GPS types, an epoch written twice and a
# header INTERVAL the data contradict gives the walk's solutions exactly.
edit obs-time-system "$walk/walk.obs" bdt.obs BDT -14
edit obs-new-types "$walk/walk.obs" new_types.obs 200
edit obs-repeat-epoch "$walk/walk.obs" repeated.obs 100
edit obs-header-record "$walk/walk.obs" interval.obs "     0.100" INTERVAL
for case in bdt new_types repeated interval; do
  fuse $case --obs $case.obs
  check "$case.obs: the walk's solutions" 'cmp -s walk/pvt.csv $case/pvt.csv'
done
check_json_each bdt/summary.json "time system BDT" observation_file.time_system == '"BDT"'
check_json_each new_types/summary.json "one type change" observation_file.observation_type_changes == 1 \
  "one event" observation_file.event_epochs == 1
check_json_each repeated/summary.json "one repeated epoch" observation_file.repeated_epochs == 1 \
  "its warning" observation_file.warnings.0 contains '"1 epoch(s) repeat the epoch before them"'
check "repeated.obs: warned, naming the line" \
  'grep -q "warning: repeated.obs:1807: 1 epoch(s) repeat the epoch before them record for record: skipped" repeated.log'
check_json_each interval/summary.json "the data's interval" observation_file.interval_s == 0.25 \
  "the header's" observation_file.header_interval_s == 0.1 \
  "no smoothing restart more than the walk's" fusion.smoothing_restarts == "$(json_value walk/summary.json fusion.smoothing_restarts)"
check "interval.obs: warned, naming the record" \
  'grep -q "warning: interval.obs:24: INTERVAL says 0.1 s, but the epochs are 0.25 s apart" interval.log'

# Where the IMU log has no data. Lines 5001-6000 of the log leave none from 33.94 s to
# 40.57 s (since the first epoch); the first 10000 lines end at 67.04 s.
edit imu-drop-rows "$walk/imu_1730.csv" imu_gap.csv 5001 6000
edit imu-drop-rows "$walk/imu_1730.csv" imu_end.csv 10001 0
fuse gap --imu imu_gap.csv
check "imu_gap.csv: the gap logged with the file and line" \
  'grep -qF "IMU data missing from t = 33.942 s to 40.568 s (imu_gap.csv line 5001): INS stopped" gap.log'
check_py "imu_gap.csv: single point only inside the gap" -m checks.fuse_integrity imu-gap gap 33.94 40.57
fuse end --imu imu_end.csv
check "imu_end.csv: the end logged" \
  'grep -q "the IMU log ends at t = 67.04 s but the observations go on to t = 133.75 s: INS stopped" end.log'
check_py "imu_end.csv: single point only after the end" -m checks.fuse_integrity imu-end end 67.04
# A row written twice is dropped, with a warning; two rows swapped are refused.
edit imu-repeat-row "$walk/imu_1730.csv" imu_twice.csv 3000
fuse twice --imu imu_twice.csv
check_json_each twice/summary.json "one row written twice" imu_log.duplicate_rows == 1
check "imu_twice.csv: warned, naming the line" \
  'grep -q "imu_twice.csv:3001: 1 row(s) repeat the row before them, time and values: dropped" twice.log'
edit imu-swap-rows "$walk/imu_1730.csv" imu_swapped.csv 4000
bad_fuse() { "$deepnav" -q fuse --config "$walk/walk.yaml" --out bad "$@"; }
expect_nothing_written() {  # NAME FRAGMENT -- OPTIONS...: refused naming FRAGMENT, no output folder
  local name=$1 fragment=$2
  shift 3
  rm -rf bad
  expect_failure "$name" "$fragment" -- bad_fuse "$@"
  if [[ $last_check == ok ]]; then check "$name: nothing written" '[[ ! -e bad ]]'; fi
}
rm -rf bad
expect_failure "IMU rows swapped" --grep "imu_swapped.csv:4001: time [0-9]* goes back before line 4000's" -- \
  bad_fuse --imu imu_swapped.csv
check "IMU rows swapped: nothing written" '[[ ! -e bad ]]'

# Observation files that cannot be read as GPS time, or have no GPS at all.
edit obs-time-system "$walk/walk.obs" glo.obs GLO -18
expect_nothing_written "GLO tags without LEAP SECONDS" \
  "glo.obs:16: TIME OF FIRST OBS: time system GLO (UTC) needs the leap seconds" -- --obs glo.obs
edit obs-header-record glo.obs glo_leap.obs "    18" "LEAP SECONDS"
fuse glo_leap --obs glo_leap.obs
check "GLO tags with LEAP SECONDS: the walk's solutions" 'cmp -s walk/pvt.csv glo_leap/pvt.csv'
edit obs-without "$walk/walk.obs" no_gps.obs G
expect_nothing_written "no GPS at all" "--obs no_gps.obs: no GPS L1 C/A observation in its 536 epochs" -- \
  --obs no_gps.obs

# Numeric options out of range, on the command line and in the configuration file.
EXIT_STATUS=105 expect_nothing_written "Doppler sigma 0" "--doppler-sigma: 0 is outside" -- --doppler-sigma 0
EXIT_STATUS=105 expect_nothing_written "IMU position 1e6 m" "--imu-position: 1e6 is outside [-100, 100]" -- \
  --imu-position 1e6 0 0
EXIT_STATUS=105 expect_nothing_written "IMU mounting NaN" "--imu-mounting: 'nan' is not a finite number" -- \
  --imu-mounting nan 0 0
EXIT_STATUS=105 expect_nothing_written "IMU time offset 1e300" "--imu-time-offset: 1e300 is outside" -- \
  --imu-time-offset 1e300
printf 'pseudorange-sigma-scale: -1\n' > negative.yaml
expect_failure "a negative scale in a configuration file" \
  "negative.yaml:1: key 'pseudorange-sigma-scale': -1 is outside" -- "$deepnav" -q fuse --config negative.yaml --out bad
check "a negative scale in a configuration file: nothing written" '[[ ! -e bad ]]'

# No epoch scored against a reference (its dates a day off): no statistic, not 0.00 m.
edit pos-shift-days "$walk/gnss_1730_sf.pos" day_off.pos 1
fuse day_off --reference day_off.pos
check "no epoch scored: said so" 'grep -q "against the reference: no epoch scored" day_off.log'
check "no epoch scored: no 0.00 m" '! grep -q "0.00 m" day_off.log'
check_py "no epoch scored: null statistics" -m checks.fuse_integrity no-score day_off
finish
