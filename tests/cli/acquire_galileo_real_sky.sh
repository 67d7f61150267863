#!/usr/bin/env bash
# `deepnav acquire --systems gps,galileo` on the real 4 MHz capture: the Galileo satellites
# GNSS-SDR finds there (results/galileo_acquisition) with their Doppler and delay, the GPS
# results identical to a GPS-only run, a system column in the table; unknown systems refused.
#   usage: acquire_galileo_real_sky.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
metadata=$src/data/L1_20211202_084700_4MHz_IQ.xml
"$deepnav" acquire --metadata "$metadata" --json "$work/gps.json" > "$work/gps_table.txt" || abort "GPS-only acquire"
"$deepnav" acquire --metadata "$metadata" --systems gps,galileo --json "$work/both.json" > "$work/table.txt" \
  || abort "acquire --systems gps,galileo"
check_py "Galileo E07 E15 E19 E20 E21 E27 E30 and GPS unchanged" -m checks.galileo_acquisition "$work/both.json" \
  "$work/gps.json" L1_20211202_084700_4MHz_IQ --gps-also 18
check "the table has a system column" 'grep -q "^ system  PRN" "$work/table.txt"'
check "the table lists E27" 'grep -q "^galileo   27 " "$work/table.txt"'
check "the table lists G31" 'grep -q "^    gps   31 " "$work/table.txt"'
check "the GPS-only table has no system column" 'grep -q "^ PRN " "$work/gps_table.txt"'
expect_failure "unknown system" "--systems: 'glonass' is not a system" -- \
  "$deepnav" acquire --metadata "$metadata" --systems gps,glonass
expect_failure "Galileo below 4 MHz" "Galileo acquisition: sample rate" -- \
  "$deepnav" acquire --input "$src/data/L1_20211202_084700_4MHz_IQ.bin" --format ibyte --fs 2500000 --systems galileo
finish
