#!/usr/bin/env bash
# Raw UDP (bare samples, no frames) whose datagrams end inside a sample: `deepnav serve --raw
# --udp` sends 2-byte ibyte samples, and the relay (tests/cli/pylib/peers/udp_impair.py
# --rechunk) sends them on in 1001-byte datagrams, as a sender cutting its byte stream
# anywhere would. The receiver once dropped each datagram's odd byte, shifting I into Q for
# every later sample (no satellite, no warning), and counted no byte of a raw UDP stream. It
# must carry the half sample into the next datagram, warn once, count every byte the relay
# sent, and track the satellites.
#   usage: stream_udp_raw_split.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
relay_py=$peers/udp_impair.py
derive_scenario "$src/data/scenarios/default.yaml" "$work/s.yaml" 'duration_s: 3' 'sample_rate_hz: 2048000'
start_background server "$deepnav" -q serve --scenario "$work/s.yaml" --udp 0 --raw --sessions 1 \
  --udp-frame-bytes 8192 --port-file "$work/server_port"
server_port=$(port_from "$work/server_port" udp)
start_background relay "$python" -S "$relay_py" relay --server "127.0.0.1:$server_port" --port-file "$work/relay_port" \
  --report "$work/relay.json" --rechunk 1001 --idle-timeout 2
relay_port=$(port_from "$work/relay_port" udp)
"$deepnav" run --input "udp://127.0.0.1:$relay_port" --raw --format ibyte --fs 2048000 --reconnect-timeout 1 \
  --week 2190 --out "$work/run" > "$work/run.log" 2>&1 || fail "raw UDP run: exit status $?: $(tail -3 "$work/run.log")"
reap $server || fail "serve exit status"
reap $relay || fail "relay exit status"
check "warned once of a datagram ending inside a sample" \
  '[[ $(grep -c "ends inside a ibyte sample (2 bytes each)" "$work/run.log") -eq 1 ]]'
sent=$(json_value "$work/relay.json" rechunked.bytes)
check "the relay sent 3 s of samples in odd datagrams" '[[ $sent -eq $((3 * 2048000 * 2)) ]]'
check_json_each "$work/run/summary.json" \
  "every byte the relay sent counted" stream.bytes_received == "$sent" \
  "datagrams ending inside a sample counted" stream.datagrams_split_samples '>' 1000 \
  "the satellites found in the realigned samples" 'len(acquired_prns)' '>=' 5 \
  "no error" error == null
finish
