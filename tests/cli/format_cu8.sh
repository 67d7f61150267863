#!/usr/bin/env bash
# cu8 (unsigned 8-bit I/Q, zero at 127.5, as an RTL-SDR writes it) round trip: a static
# scenario is synthesized at 2.048 Msps with an 8-bit ADC into if_cu8.bin, and the receiver
# (assisted start) fixes from it within a few metres of the truth; run from the metadata file
# the synthesizer wrote beside it, and served over TCP (framed, as fast as read), it gives the
# same fixes. A misspelt format names the accepted
# ones and exits non-zero.
#   usage: format_cu8.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
server=
trap '[[ -n $server ]] && kill $server 2>/dev/null; rm -rf "$work"' EXIT
fail() { echo "FAIL $*"; exit 1; }
sed -e 's/duration_s: 120/duration_s: 24/' -e 's/sample_rate_hz: 2600000/sample_rate_hz: 2048000/' \
    -e 's/format: ibyte/format: cu8/' -e 's/adc: {bits: 4, agc: true}/adc: {bits: 8, agc: true}/' \
    "$src/data/scenarios/static_120s.yaml" > "$work/s.yaml"
"$deepnav" -q sim --scenario "$work/s.yaml" --out "$work/sim" > /dev/null || fail sim
[[ -s $work/sim/if_cu8.bin ]] || fail "sim wrote no if_cu8.bin"
[[ $(stat -c %s "$work/sim/if_cu8.bin") -eq $((24 * 2048000 * 2)) ]] || fail "if_cu8.bin is not 2 bytes a sample"
"$deepnav" -q run --input "$work/sim/if_cu8.bin" --format cu8 --fs 2048000 --week 2190 \
  --iono-from "$src/data/brdc0010.22n" --ephemeris-from "$src/data/brdc0010.22n" \
  --truth "$work/sim/truth.csv" --out "$work/run" > /dev/null || fail "run"
python3 - "$work/run/summary.json" <<'PY' || exit 1
import json, sys
s = json.load(open(sys.argv[1]))
h = s["horizontal_error_m"]["rms"]
checks = [("fixes >= 5", s["fixes"] >= 5, s["fixes"]), ("horizontal RMS <= 5 m", h <= 5.0, h)]
bad = 0
for name, ok, value in checks:
    print(("ok  " if ok else "FAIL"), "cu8:", name, value)
    bad += not ok
sys.exit(1 if bad else 0)
PY
"$deepnav" -q run --metadata "$work/sim/if_cu8.xml" --week 2190 \
  --iono-from "$src/data/brdc0010.22n" --ephemeris-from "$src/data/brdc0010.22n" --out "$work/meta" > /dev/null \
  || fail "run --metadata"
cmp -s "$work/run/pvt.csv" "$work/meta/pvt.csv" || fail "pvt.csv from --metadata differs from the flags run's"
echo "ok   cu8 from if_cu8.xml alone: pvt.csv identical to the flags run's"
"$deepnav" -q serve --file "$work/sim/if_cu8.bin" --format cu8 --fs 2048000 --tcp 0 --pace 0 --sessions 1 \
  --port-file "$work/ports" &
server=$!
for _ in $(seq 100); do [[ -s $work/ports ]] && break; sleep 0.1; done
port=$(awk '$1 == "tcp" {print $2}' "$work/ports" 2>/dev/null)
[[ -n $port ]] || fail "serve did not report its port"
"$deepnav" -q run --input "tcp://127.0.0.1:$port" --week 2190 \
  --iono-from "$src/data/brdc0010.22n" --ephemeris-from "$src/data/brdc0010.22n" --out "$work/tcp" > /dev/null \
  || fail "tcp run"
wait $server || fail "serve exit status"
server=
cmp -s "$work/run/pvt.csv" "$work/tcp/pvt.csv" || fail "pvt.csv over TCP differs from the file run's"
echo "ok   cu8 over tcp://: pvt.csv identical to the file run's"
msg=$("$deepnav" -q run --input "$work/sim/if_cu8.bin" --format cu9 --fs 2048000 --out "$work/bad" 2>&1)
rc=$?
[[ $rc -ne 0 && $msg == *"cu9"*"cu8"* ]] || fail "--format cu9: exit $rc, message: $msg"
echo "ok   --format cu9: exit $rc, $(head -1 <<< "$msg")"
