#!/usr/bin/env bash
# RTKLIB reads our mixed RINEX 3 products back: a GPS+Galileo run's obs.rnx with the
# assisted navigation file goes through `rnx2rtkp -sys G,E` (scripts/rtklib_check.sh), and
# every RTKLIB fix uses both systems' satellites and lies within 1 m of our own fix of the
# same epoch. The scenario is the bundled mixed one at 23:50 (7 GPS and 3 Galileo satellites
# there, every Galileo record's toe before the epoch: RTKLIB 2.4.3 refuses Galileo records
# whose toe is still to come), at 50 dB-Hz and without ionosphere and troposphere on either
# side, so the two solvers' different weightings (RTKLIB: URA/SISA and model variances; ours:
# elevation and C/N0) act on little noise and no model residual.
#   usage: rtklib_mixed_readback.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
command -v rnx2rtkp > /dev/null || abort "rnx2rtkp is not installed (scripts/install_deps.sh installs rtklib)"

nav="$src/data/gps_galileo_20220101.rnx"
derive_scenario "$src/data/scenarios/static_gps_galileo_60s.yaml" "$work/mixed.yaml" \
  'start_time: "2022-01-01T23:50:00"' 'cn0: 50' 'ionosphere: false' 'troposphere: false'
sim_scenario "$work/mixed.yaml" "$work/sim" --duration 30
run_on_sim "$work/sim" "$work/run" --systems gps,galileo --ephemeris-from "$nav" --ionosphere none \
  --troposphere none
check "obs.rnx holds Galileo observations" 'grep -q "^E[0-9][0-9] " "$work/run/obs.rnx"'
check "RTKLIB -sys G,E: every fix within 1 m of ours, from at least 9 satellites of both systems" \
  'bash "$src/scripts/rtklib_check.sh" "$work/run" --sys G,E --nav "$nav" --atmosphere none --bound 1 \
     --min-satellites 9 >> "$work/rtklib.log" 2>&1'
cat "$work/rtklib.log"
finish
