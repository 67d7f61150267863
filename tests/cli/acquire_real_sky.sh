#!/usr/bin/env bash
# `deepnav acquire` on the real 4 MHz capture: JSON output lists the expected PRNs
# with their Doppler and delay; a wrong sample rate finds nothing: exit status 3 and a
# hint naming --fs.
#   usage: acquire_real_sky.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
capture=$src/data/L1_20211202_084700_4MHz_IQ.bin
"$deepnav" acquire --input "$capture" --format ibyte --fs 4000000 --inverted-spectrum --json "$work/acq.json" \
  > "$work/table.txt" || abort "acquire exit status"
check_py "the expected satellites, only those and PRN 18, of 32 searched" -m checks.acquisition "$work/acq.json" \
  L1_20211202_084700_4MHz_IQ --searched 32 --no-others-but 18
check "the table lists PRN 31" 'grep -q "^  31 " "$work/table.txt"'
EXIT_STATUS=3 expect_failure "wrong --fs" "no satellite found in 10 ms of signal" "--fs 2500000" -- "$deepnav" acquire --input "$capture" --format ibyte --fs 2500000
expect_failure "bad --format" "--format" -- "$deepnav" acquire --input "$capture" --format int4 --fs 4000000
finish
