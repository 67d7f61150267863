#!/usr/bin/env bash
# UDP with injected frame loss: `deepnav serve` never sends frames 5-7, 100 and 250; the
# receiver must report exactly those frames lost, and their samples as gaps at the right
# sample indices (4096 samples per 8192-byte ibyte frame), nothing else.
#   usage: stream_udp_loss.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
server=
trap '[[ -n $server ]] && kill $server 2>/dev/null; rm -rf "$work"' EXIT
fail() { echo "FAIL $*"; exit 1; }
"$deepnav" -q serve --scenario "$src/data/scenarios/default.yaml" --duration 3 --udp 0 --pace 4 --sessions 1 \
  --udp-frame-bytes 8192 --drop-frames 5,6,7,100,250 --port-file "$work/ports" &
server=$!
for _ in $(seq 100); do [[ -s $work/ports ]] && break; sleep 0.1; done
port=$(awk '$1 == "udp" {print $2}' "$work/ports" 2>/dev/null)
[[ -n $port ]] || fail "serve did not report its port"
"$deepnav" -q run --input "udp://127.0.0.1:$port" --week 2190 --out "$work/udp" > /dev/null || fail "udp run"
wait $server || fail "serve exit status"
server=
python3 - "$work/udp/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["stream"]
n = 4096
expected_gaps = [{"first_missing_sample": 5 * n, "missing_samples": 3 * n},
                 {"first_missing_sample": 100 * n, "missing_samples": n},
                 {"first_missing_sample": 250 * n, "missing_samples": n}]
checks = [
    ("lost frame ranges [[5,7],[100,100],[250,250]]", s["lost_frame_ranges"] == [[5, 7], [100, 100], [250, 250]], s["lost_frame_ranges"]),
    ("5 frames lost", s["frames_lost"] == 5, s["frames_lost"]),
    ("gaps at the dropped frames' samples", s["gaps"] == expected_gaps, s["gaps"]),
    ("lost samples = 5 frames", s["lost_samples"] == 5 * n, s["lost_samples"]),
    ("no overrun, duplicate or late frame", s["frames_overrun"] == 0 and s["frames_duplicated"] == 0 and s["frames_late"] == 0, s),
    ("all other frames received", s["frames_received"] == 3 * 4092000 // n + 1 - 5, s["frames_received"]),
    ("ended normally", s["end"] == "end of stream" and not s["failed"], s["end"]),
]
bad = 0
for name, ok, value in checks:
    print(("ok  " if ok else "FAIL"), name, value)
    bad += not ok
sys.exit(1 if bad else 0)
PY
