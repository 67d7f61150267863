#!/usr/bin/env bash
# Streaming over TCP loopback gives the same products as the file: a 4 s scenario is
# synthesized to a file and run from it; the same scenario is synthesized on the fly by
# `deepnav serve` (as fast as the client reads) and run from tcp://; every product must be
# byte-identical (the track names and summary.json's input name apart, and its stream statistics).
#   usage: stream_tcp_identical.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
scenario=$src/data/scenarios/default.yaml
sim_scenario "$scenario" "$work/sim" --duration 4
run_on_sim "$work/sim" "$work/file"
start_background server "$deepnav" -q serve --scenario "$scenario" --duration 4 --tcp 0 --pace 0 --sessions 1 \
  --port-file "$work/ports"
port=$(port_from "$work/ports" tcp)
run_receiver "$work/tcp" --input "tcp://127.0.0.1:$port" --week "$(week_of "$work/sim")"
reap $server || fail "serve exit status"
for f in pvt.csv tracking.csv obs.rnx nav.rnx fixes.nmea; do
  check "$f identical" 'cmp -s "$work/file/$f" "$work/tcp/$f"'
done
# The tracks are named after the input (file name vs URL); everything else must match.
unnamed() { sed 's#<name>[^<]*</name>#<name/>#' "$1"; }
for f in track.kml track.gpx; do
  check "$f identical but for its name" 'cmp -s <(unnamed "$work/file/$f") <(unnamed "$work/tcp/$f")'
done
check "tracking.csv has over 1000 rows" '[[ $(wc -l < "$work/file/tracking.csv") -gt 1000 ]]'
check "summary.json identical but for the input, the resources and the stream" \
  'py -m query same "$work/file/summary.json" "$work/tcp/summary.json" --ignore input resources stream'
check_json_each "$work/tcp/summary.json" \
  "tcp: no lost sample" stream.lost_samples '==' 0 \
  "tcp: no gap" stream.gaps '==' '[]' \
  "tcp: the stream did not fail" stream.failed '==' false \
  "tcp: ended at the end of the stream" stream.end '==' '"end of stream"'
check_json_each "$work/file/summary.json" \
  "not interrupted" interrupted '==' false \
  "the file run has no stream statistics" . lacks '"stream"'
finish
