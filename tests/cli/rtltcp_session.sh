#!/usr/bin/env bash
# rtl_tcp client against a small rtl_tcp-protocol server (tests/cli/lib/rtltcp_server.py,
# loopback): a static scenario synthesized as cu8 at 2.048 Msps is served in real time as a
# dongle would send it, with 0.25 s of samples dropped at 17 s. `deepnav run --input
# rtltcp://` reads the dongle header, sends the tuning (sample rate, 1575.42 MHz, ppm, manual
# gain, RTL AGC, bias tee: checked as the server received them), fixes within a few metres,
# and reports the dropped samples as lost (count within 20 ms of what the server left out).
# Not an rtl_tcp server, nobody listening, or a format other than cu8: clear errors.
#   usage: rtltcp_session.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
echo "work: $work"
server=
trap '[[ -n $server ]] && kill $server 2>/dev/null; [[ -n ${KEEP:-} ]] || rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
sed -e 's/duration_s: 120/duration_s: 22/' -e 's/sample_rate_hz: 2600000/sample_rate_hz: 2048000/' \
    -e 's/format: ibyte/format: cu8/' -e 's/adc: {bits: 4, agc: true}/adc: {bits: 8, agc: true}/' \
    "$src/data/scenarios/static_120s.yaml" > "$work/s.yaml"
"$deepnav" -q sim --scenario "$work/s.yaml" --out "$work/sim" > /dev/null || { echo "FAIL sim"; exit 1; }

python3 "$src/tests/cli/lib/rtltcp_server.py" "$work/sim/if_cu8.bin" --rate 2048000 --port-file "$work/port" \
  --commands "$work/commands.txt" --drop-at 17 --drop-seconds 0.25 2> "$work/server.log" &
server=$!
for _ in $(seq 100); do [[ -s $work/port ]] && break; sleep 0.1; done
port=$(cat "$work/port" 2>/dev/null)
[[ -n $port ]] || { echo "FAIL the test server did not report its port"; exit 1; }
"$deepnav" run --input "rtltcp://127.0.0.1:$port" --rtl-gain 40.2 --rtl-ppm -3 --rtl-agc --rtl-bias-tee --week 2190 \
  --iono-from "$src/data/brdc0010.22n" --ephemeris-from "$src/data/brdc0010.22n" --truth "$work/sim/truth.csv" \
  --out "$work/run" > "$work/run.log" 2>&1 || { fail "run over rtltcp://"; cat "$work/run.log"; }
wait $server || fail "test server exit status"
server=
dropped=$(sed -n 's/.*dropped \([0-9]*\) samples.*/\1/p' "$work/server.log")
echo "server: $(tail -1 "$work/server.log")"
grep -E "R820T|missing|lost" "$work/run.log" | head -4
python3 - "$work/run/summary.json" "$work/commands.txt" "${dropped:-0}" <<'PY' || failures=$((failures + 1))
import json, sys
s = json.load(open(sys.argv[1]))
commands = dict(line.split() for line in open(sys.argv[2]) if line.strip())
dropped = int(sys.argv[3])
st = s["stream"]
want = {"sample_rate": "2048000", "frequency": "1575420000", "freq_correction": str(2**32 - 3), "gain_mode": "1",
        "gain": "402", "agc_mode": "1", "bias_tee": "1"}
h = s["horizontal_error_m"]["rms"] if s["fixes"] else float("nan")
checks = [
    ("tuning commands as sent", all(commands.get(k) == v for k, v in want.items()), commands),
    ("dongle header read (R820T, 29 gain steps)", st["dongle"]["tuner"] == "R820T" and st["dongle"]["gain_steps"] == 29, st["dongle"]),
    ("fixes >= 3", s["fixes"] >= 3, s["fixes"]),
    ("horizontal RMS <= 6 m", h <= 6.0, h),
    ("the server dropped samples", dropped > 400000, dropped),
    ("lost samples within 20 ms of those dropped", abs(st["lost_samples"] - dropped) <= 0.020 * 2048000,
     f'{st["lost_samples"]} lost in {len(st["gaps"])} gap(s) {st["gaps"]}'),
    ("one gap", len(st["gaps"]) == 1, st["gaps"]),
    ("the stream ended normally", not st["failed"], st["end"]),
]
bad = 0
for name, ok, value in checks:
    print(("ok  " if ok else "FAIL"), name, value)
    bad += not ok
sys.exit(1 if bad else 0)
PY

expect_error() {  # expect_error TEXT -- COMMAND...
  local text=$1 msg rc
  shift 2
  msg=$("$@" 2>&1)
  rc=$?
  if [[ $rc -eq 0 || $msg != *"$text"* ]]; then fail "$*: exit $rc, message: $msg"; else echo "ok   exit $rc: $(head -1 <<< "$msg")"; fi
}
# A server that is not rtl_tcp.
python3 -c '
import socket, sys
s = socket.socket(); s.bind(("127.0.0.1", 0)); s.listen(1)
open(sys.argv[1], "w").write(str(s.getsockname()[1]))
c, _ = s.accept(); c.sendall(b"HTTP/1.0 200 OK\r\n\r\n"); c.recv(100); c.close()
' "$work/port2" &
server=$!
for _ in $(seq 100); do [[ -s $work/port2 ]] && break; sleep 0.1; done
expect_error 'magic is "HTTP", expected "RTL0"' -- "$deepnav" -q run --input "rtltcp://127.0.0.1:$(cat "$work/port2")" --out "$work/bad"
wait $server 2>/dev/null
server=
expect_error "rtltcp://127.0.0.1:9: cannot connect" -- "$deepnav" -q run --input rtltcp://127.0.0.1:9 --out "$work/bad"
expect_error "an rtl_tcp server sends cu8" -- "$deepnav" -q run --input rtltcp://127.0.0.1:9 --format ibyte --out "$work/bad"
expect_error "not one the RTL2832 makes" -- "$deepnav" -q run --input rtltcp://127.0.0.1:9 --fs 5000000 --out "$work/bad"
exit $((failures > 0))
