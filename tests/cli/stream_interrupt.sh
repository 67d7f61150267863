#!/usr/bin/env bash
# Ctrl-C during a streamed run: `deepnav run` on a real-time TCP stream gets SIGINT after
# 4 s; it must exit 130 (as a shell reports Ctrl-C; it exited 0, like a complete run) with
# every product written (no .partial file) and summary.json saying it was interrupted
# before the stream's end, and the server must end the session.
#   usage: stream_interrupt.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
duration_s=30
start_background server "$deepnav" -q serve --scenario "$src/data/scenarios/default.yaml" --duration $duration_s \
  --tcp 0 --pace 1 --sessions 1 --port-file "$work/ports"
port=$(port_from "$work/ports" tcp)
start_background run "$deepnav" -q run --input "tcp://127.0.0.1:$port" --week 2190 --out "$work/run" > /dev/null \
  2> "$work/run.err"
sleep 4
kill -INT $run
status=0
reap $run || status=$?
[[ $status -eq 130 ]] || abort "run exit status $status after SIGINT, expected 130: $(cat "$work/run.err")"
check "the message says interrupted by SIGINT" 'grep -q "deepnav: interrupted by SIGINT: the products are written" "$work/run.err"'
for _ in $(seq 50); do kill -0 $server 2>/dev/null || break; sleep 0.1; done
check "serve ends after its only client left" '! kill -0 $server 2>/dev/null'
for f in pvt.csv tracking.csv obs.rnx nav.rnx fixes.nmea track.kml track.gpx summary.json; do
  check "$f written" '[[ -f $work/run/$f ]]'
done
check "no .partial file left" '! ls "$work/run" | grep -q partial'
# How much signal arrived in 4 s depends on the machine (a sanitizer build on a busy
# machine may get only a few blocks); that it stopped before the stream's end does not.
check_json_each "$work/run/summary.json" \
  "summary.json: interrupted" interrupted '==' true \
  "some signal processed" duration_s '>' 0.0 \
  "stopped before the stream's end" duration_s '<' $((duration_s - 1)).0 \
  "the stream's end: interrupted" stream.end '==' '"interrupted"' \
  "the stream did not fail" stream.failed '==' false
finish
