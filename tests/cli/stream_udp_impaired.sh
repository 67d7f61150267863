#!/usr/bin/env bash
# UDP through an impairing relay (tests/cli/lib/udp_impair.py) on loopback: frames dropped
# (a run, a single one, one just before a held-back frame, and the last data frame),
# duplicated, and reordered at the edge of the receiver's tolerance and just past it, plus
# seeded random ones. The receiver must
# report exactly what the relay did: the dropped frames as lost ranges and their samples
# as gaps, the duplicates counted, a frame held back across up to 63 frames as reordered
# (UdpSampleSource::kReorderWindow = 64: one held across 64 was declared lost first and
# arrives late), and nothing else.
#   usage: stream_udp_impaired.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
relay_py=$src/tests/cli/lib/udp_impair.py
work=$(mktemp -d)
server= relay=
trap '[[ -n $relay ]] && kill $relay 2>/dev/null; [[ -n $server ]] && kill $server 2>/dev/null; rm -rf "$work"' EXIT
fail() { echo "FAIL $*"; exit 1; }
port_from() {  # port_from FILE: the "udp N" line its writer puts there once listening
  for _ in $(seq 100); do [[ -s $1 ]] && break; sleep 0.1; done
  awk '$1 == "udp" {print $2}' "$1" 2>/dev/null
}

# 3 s at 4.092 Msps in 8192-byte ibyte frames: frames 0..2997 of 4096 samples, the last of 288.
"$deepnav" -q serve --scenario "$src/data/scenarios/default.yaml" --duration 3 --udp 0 --pace 4 --sessions 1 \
  --udp-frame-bytes 8192 --port-file "$work/server_port" &
server=$!
server_port=$(port_from "$work/server_port")
[[ -n $server_port ]] || fail "serve did not report its port"
python3 "$relay_py" relay --server "127.0.0.1:$server_port" --port-file "$work/relay_port" --report "$work/relay.json" \
  --seed 20 --drop 5,6,7,100,1000,2997 --duplicate 40,41,200 --reorder 300:1,400:5,500:63,700:64,1001:63 \
  --drop-fraction 0.003 --duplicate-fraction 0.003 --reorder-fraction 0.003 --reorder-depth 8 --idle-timeout 15 &
relay=$!
relay_port=$(port_from "$work/relay_port")
[[ -n $relay_port ]] || fail "the relay did not report its port"
"$deepnav" -q run --input "udp://127.0.0.1:$relay_port" --week 2190 --out "$work/udp" > /dev/null || fail "udp run"
wait $server || fail "serve exit status"
server=
wait $relay || fail "relay exit status"
relay=

# The relay did what was asked (so the comparison below tests the receiver, not the relay)...
python3 - "$work/relay.json" <<'PY' || exit 1
import json, sys
r = json.load(open(sys.argv[1]))
dropped = {d["sequence"] for d in r["dropped"]}
duplicated = {d["sequence"] for d in r["duplicated"]}
reordered = {x["sequence"]: x["displacement"] for x in r["reordered"]}
checks = [
    ("the stream ended normally", r["ended_by"] == "end of stream", r["ended_by"]),
    ("2998 frames from the server", r["frames_from_server"] == 2998, r["frames_from_server"]),
    ("dropped 5-7, 100 and the last frame 2997 (288 samples)",
     {5, 6, 7, 100, 2997} <= dropped and r["dropped"][-1] == {"sequence": 2997, "first_sample": 2997 * 4096, "samples": 288},
     sorted(dropped)),
    ("duplicated 40, 41, 200", {40, 41, 200} <= duplicated, sorted(duplicated)),
    ("reordered 300:1, 400:5, 500:63, 700:64",
     all(reordered.get(s) == k for s, k in {300: 1, 400: 5, 500: 63, 700: 64}.items()), reordered),
    ("seeded impairments besides the explicit ones",
     len(dropped) > 5 and len(duplicated) > 3 and len(reordered) > 4, (len(dropped), len(duplicated), len(reordered))),
]
bad = 0
for name, ok, value in checks:
    print(("ok  " if ok else "FAIL"), "relay:", name, value)
    bad += not ok
sys.exit(1 if bad else 0)
PY
# ...and the receiver reported exactly that.
python3 "$relay_py" compare --report "$work/relay.json" --summary "$work/udp/summary.json" \
  || fail "the receiver's stream report differs from what the relay did (above)"
