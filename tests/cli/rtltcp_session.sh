#!/usr/bin/env bash
# rtl_tcp client against a small rtl_tcp-protocol server (tests/cli/pylib/peers/rtltcp_server.py,
# loopback): a static scenario synthesized as cu8 at 2.048 Msps is served in real time as a
# dongle would send it, with 0.25 s of samples dropped at 17 s. `deepnav run --input
# rtltcp://` reads the dongle header, sends the tuning (sample rate, 1575.42 MHz, ppm, manual
# gain, RTL AGC, bias tee: checked as the server received them), fixes within a few metres,
# and reports the dropped samples as lost (count within 20 ms of what the server left out).
# Not an rtl_tcp server, nobody listening, or a format other than cu8: clear errors.
#   usage: rtltcp_session.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
derive_scenario "$src/data/scenarios/static_120s.yaml" "$work/s.yaml" 'duration_s: 22' 'sample_rate_hz: 2048000' \
  'format: cu8' 'adc: {bits: 8, agc: true}'
sim_scenario "$work/s.yaml" "$work/sim"
fs=$(sample_rate_of "$work/sim")
start_background server "$python" -S "$peers/rtltcp_server.py" "$work/sim/if_cu8.bin" --rate "$fs" --port-file "$work/port" \
  --commands "$work/commands.txt" --drop-at 17 --drop-seconds 0.25 2> "$work/server.log"
port=$(port_from "$work/port")
"$deepnav" run --input "rtltcp://127.0.0.1:$port" --rtl-gain 40.2 --rtl-ppm -3 --rtl-agc --rtl-bias-tee \
  --week "$(week_of "$work/sim")" "${assisted[@]}" --truth "$work/sim/truth.csv" --out "$work/run" > "$work/run.log" 2>&1 ||
  abort "run over rtltcp://: $(cat "$work/run.log")"
reap $server || fail "test server exit status"
dropped=$(sed -n 's/.*dropped \([0-9]*\) samples.*/\1/p' "$work/server.log")
echo "server: $(tail -1 "$work/server.log")"
grep -E "R820T|missing|lost" "$work/run.log" | head -4 || true
check_py "the rtl_tcp session" -m checks.rtltcp_session "$work/run" "$work/commands.txt" "${dropped:-0}" "$fs"

start_background server "$python" -S "$peers/not_rtltcp_server.py" "$work/port2"
expect_failure "not an rtl_tcp server" 'magic is "HTTP", expected "RTL0"' -- \
  "$deepnav" -q run --input "rtltcp://127.0.0.1:$(port_from "$work/port2")" --out "$work/bad"
reap $server || true
expect_failure "nobody listening" "rtltcp://127.0.0.1:9: cannot connect" -- \
  "$deepnav" -q run --input rtltcp://127.0.0.1:9 --out "$work/bad"
expect_failure "not cu8" "an rtl_tcp server sends cu8" -- \
  "$deepnav" -q run --input rtltcp://127.0.0.1:9 --format ibyte --out "$work/bad"
expect_failure "a rate the RTL2832 does not make" "not one the RTL2832 makes" -- \
  "$deepnav" -q run --input rtltcp://127.0.0.1:9 --fs 5000000 --out "$work/bad"
finish
