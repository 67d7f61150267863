#!/usr/bin/env bash
# UDP through an impairing relay (tests/cli/pylib/peers/udp_impair.py) on loopback: frames
# dropped (a run, a single one, one just before a held-back frame, and the last data frame),
# duplicated, and reordered at the edge of the receiver's tolerance and just past it, plus
# seeded random ones. The receiver must
# report exactly what the relay did: the dropped frames as lost ranges and their samples
# as gaps, the duplicates counted, a frame held back across up to 63 frames as reordered
# (UdpSampleSource::kReorderWindow = 64: one held across 64 was declared lost first and
# arrives late), and nothing else.
#   usage: stream_udp_impaired.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
relay_py=$peers/udp_impair.py
# 3 s at 4.092 Msps in 8192-byte ibyte frames: frames 0..2997 of 4096 samples, the last of 288.
start_background server "$deepnav" -q serve --scenario "$src/data/scenarios/default.yaml" --duration 3 --udp 0 --pace 4 \
  --sessions 1 --udp-frame-bytes 8192 --port-file "$work/server_port"
server_port=$(port_from "$work/server_port" udp)
start_background relay "$python" -S "$relay_py" relay --server "127.0.0.1:$server_port" --port-file "$work/relay_port" \
  --report "$work/relay.json" --seed 20 --drop 5,6,7,100,1000,2997 --duplicate 40,41,200 \
  --reorder 300:1,400:5,500:63,700:64,1001:63 --drop-fraction 0.003 --duplicate-fraction 0.003 \
  --reorder-fraction 0.003 --reorder-depth 8 --idle-timeout 15
relay_port=$(port_from "$work/relay_port" udp)
run_receiver "$work/udp" --input "udp://127.0.0.1:$relay_port" --week 2190
reap $server || fail "serve exit status"
reap $relay || fail "relay exit status"
# The relay did what was asked (so the comparison below tests the receiver, not the relay)...
check_py "the relay impaired the stream as asked" -m checks.udp_relay_report "$work/relay.json"
# ...and the receiver reported exactly that.
check_py "the receiver's stream report is what the relay did" "$relay_py" compare --report "$work/relay.json" \
  --summary "$work/udp/summary.json"
finish
