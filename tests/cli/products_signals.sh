#!/usr/bin/env bash
# A run that a signal stops closes its products, writes summary.json ("interrupted": true)
# and exits 128 + the signal, so that a script can tell it from a complete run (it exited
# 0): 143 for SIGTERM, 129 for SIGHUP, where the terminal is gone too (its output pipe has
# no reader: the run must not die of SIGPIPE before its products are closed, as it died of
# the hangup itself with only partial files). SIGINT (130) is stream_interrupt.sh's. A
# synthesis a signal stops leaves nothing, and exits 130. The runs read a real-time stream
# so that the signal comes mid-run on any machine.
#   usage: products_signals.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
duration_s=30
start_background server "$deepnav" -q serve --scenario "$src/data/scenarios/default.yaml" --duration $duration_s \
  --tcp 0 --pace 1 --sessions 2 --port-file "$work/ports"
port=$(port_from "$work/ports" tcp)

# wait_for_partial_files DIR: until the command writing there has opened its files.
wait_for_partial_files() {
  for _ in $(seq 100); do compgen -G "$1/*.partial" > /dev/null && return; sleep 0.1; done
  abort "no partial file in ${1##*/} after 10 s"
}

# check_interrupted_run NAME OUT STATUS EXPECTED_STATUS SIGNAL_NAME MESSAGE_FILE
check_interrupted_run() {
  local name=$1 out=$2 status=$3 expected=$4 signal=$5 messages=$6 f
  check "$name: exit $expected ($status)" '[[ $status -eq $expected ]]'
  check "$name: the message says so" \
    'grep -q "interrupted by $signal: the products are written up to sample [0-9]* (summary.json: \"interrupted\": true)" "$messages"'
  for f in pvt.csv tracking.csv obs.rnx nav.rnx fixes.nmea track.kml track.gpx summary.json; do
    check "$name: $f written" '[[ -f $out/$f ]]'
  done
  check "$name: no partial file" '! ls "$out" | grep -q partial'
  check_json_each "$out/summary.json" \
    "$name: summary.json says interrupted" interrupted '==' true \
    "$name: stopped before the stream's end" duration_s '<' $((duration_s - 1)).0 \
    "$name: no error" error '==' null
}

# SIGTERM (a service manager stopping the run).
start_background run "$deepnav" -q run --input "tcp://127.0.0.1:$port" --week 2190 --out "$work/term" \
  > "$work/term.out" 2> "$work/term.err"
wait_for_partial_files "$work/term"
sleep 1
kill -TERM $run
status=0
reap $run || status=$?
check_interrupted_run SIGTERM "$work/term" $status 143 SIGTERM "$work/term.err"

# SIGHUP with the terminal gone: the run's output goes to a pipe whose reader is killed first.
mkfifo "$work/terminal"
start_background reader cat "$work/terminal"
start_background run "$deepnav" -q run --input "tcp://127.0.0.1:$port" --week 2190 --out "$work/hup" \
  > "$work/terminal" 2>&1
wait_for_partial_files "$work/hup"
sleep 1
kill $reader
reap $reader || true
kill -HUP $run
status=0
reap $run || status=$?
check "SIGHUP: exit 129, not killed by SIGPIPE ($status)" '[[ $status -eq 129 ]]'
for f in pvt.csv tracking.csv obs.rnx nav.rnx fixes.nmea track.kml track.gpx summary.json; do
  check "SIGHUP: $f written" '[[ -f $work/hup/$f ]]'
done
check "SIGHUP: no partial file" '! ls "$work/hup" | grep -q partial'
check_json "SIGHUP: summary.json says interrupted" "$work/hup/summary.json" interrupted '==' true

# A synthesis stopped by Ctrl-C: an IF file cut short would pass for a shorter scenario.
derive_scenario "$src/data/scenarios/default.yaml" "$work/long.yaml" 'duration_s: 300'
start_background sim "$deepnav" -q sim --scenario "$work/long.yaml" --out "$work/sim" --threads 1 \
  > "$work/sim.out" 2> "$work/sim.err"
wait_for_partial_files "$work/sim"
sleep 0.5
kill -INT $sim
status=0
reap $sim || status=$?
check "sim: exit 130 ($status)" '[[ $status -eq 130 ]]'
check "sim: the message says so" \
  'grep -q "interrupted by SIGINT: nothing is written (an incomplete IF file would pass for a short one)" "$work/sim.err"'
check "sim: nothing left in its folder" '[[ -z $(ls "$work/sim") ]]'
finish
