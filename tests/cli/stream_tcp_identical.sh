#!/usr/bin/env bash
# Streaming over TCP loopback gives the same products as the file: a 4 s scenario is
# synthesized to a file and run from it; the same scenario is synthesized on the fly by
# `deepnav serve` (as fast as the client reads) and run from tcp://; every product must be
# byte-identical (the track names and summary.json's input name apart, and its stream statistics).
#   usage: stream_tcp_identical.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
server=
trap '[[ -n $server ]] && kill $server 2>/dev/null; rm -rf "$work"' EXIT
fail() { echo "FAIL $*"; exit 1; }
scenario=$src/data/scenarios/default.yaml
"$deepnav" -q sim --scenario "$scenario" --duration 4 --out "$work/sim" > /dev/null || fail sim
"$deepnav" -q run --input "$work/sim/if_ibyte.bin" --format ibyte --fs 4092000 --week 2190 --out "$work/file" > /dev/null \
  || fail "file run"
"$deepnav" -q serve --scenario "$scenario" --duration 4 --tcp 0 --pace 0 --sessions 1 --port-file "$work/ports" &
server=$!
for _ in $(seq 100); do [[ -s $work/ports ]] && break; sleep 0.1; done
port=$(awk '$1 == "tcp" {print $2}' "$work/ports" 2>/dev/null)
[[ -n $port ]] || fail "serve did not report its port"
"$deepnav" -q run --input "tcp://127.0.0.1:$port" --week 2190 --out "$work/tcp" > /dev/null || fail "tcp run"
wait $server || fail "serve exit status"
server=
bad=0
for f in pvt.csv tracking.csv obs.rnx nav.rnx fixes.nmea; do
  if cmp -s "$work/file/$f" "$work/tcp/$f"; then echo "ok   $f identical"; else echo "FAIL $f differs"; bad=1; fi
done
# The tracks are named after the input (file name vs URL); everything else must match.
for f in track.kml track.gpx; do
  if cmp -s <(sed 's#<name>[^<]*</name>#<name/>#' "$work/file/$f") <(sed 's#<name>[^<]*</name>#<name/>#' "$work/tcp/$f"); then
    echo "ok   $f identical but for its name"
  else
    echo "FAIL $f differs"; bad=1
  fi
done
[[ $(wc -l < "$work/file/tracking.csv") -gt 1000 ]] || { echo "FAIL tracking.csv nearly empty"; bad=1; }
python3 - "$work/file/summary.json" "$work/tcp/summary.json" <<'PY' || bad=1
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
stream = b.pop("stream")
for s in (a, b):
    s.pop("input")
    s.pop("resources")
assert a == b, f"summaries differ: {a} vs {b}"
assert stream["lost_samples"] == 0 and stream["gaps"] == [] and not stream["failed"], stream
assert stream["end"] == "end of stream", stream
assert a["interrupted"] is False
print("ok   summary.json identical; stream:", stream["frames_received"], "frames,", stream["bytes_received"], "bytes")
PY
exit $bad
