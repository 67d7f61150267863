#!/usr/bin/env bash
# rtl_tcp servers that are not a dongle keeping real time (tests/cli/pylib/peers/rtltcp_server.py):
#  - half real time (a file replayed slowly): rtl_tcp has no sample indices, and every piece
#    arriving later than real time was once taken for lost samples (304 invented gaps, every
#    satellite acquired again after each: "satellites acquired: 2135" for 7). A slow sender
#    is slow, not lossy: no gap, a warning with its pace, each satellite acquired once.
#  - a trickle of 2000 bytes every half second (1/1000 of real time) that stops after 6 s:
#    warned of with its pace, and as every sample it sent fell in the tuner's settling time,
#    the run has nothing to process: exit status 1 saying so, with the products and a
#    summary.json whose error says it too.
#  - the dongle header, then the connection closed: exit status 1, "without a sample to process".
#   usage: rtltcp_slow_sender.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
server_py=$peers/rtltcp_server.py
derive_scenario "$src/data/scenarios/static_120s.yaml" "$work/s.yaml" 'duration_s: 3' 'sample_rate_hz: 2048000' \
  'format: cu8' 'adc: {bits: 8, agc: true}'
sim_scenario "$work/s.yaml" "$work/sim"
fs=$(sample_rate_of "$work/sim")

# Half real time: 2.5 s of signal in 5 s.
start_background server "$python" -S "$server_py" "$work/sim/if_cu8.bin" --rate "$fs" --port-file "$work/port_half" \
  --pace 0.5 --seconds 2.5 2> "$work/server_half.log"
"$deepnav" run --input "rtltcp://127.0.0.1:$(port_from "$work/port_half")" --week "$(week_of "$work/sim")" \
  "${assisted[@]}" --out "$work/half" > "$work/half.log" 2>&1 || fail "half real time: exit status $?: $(tail -3 "$work/half.log")"
reap $server || fail "test server exit status (half real time)"
check "half real time: warned with its pace" 'grep -q "the stream runs at 0.5 of real time" "$work/half.log"'
check "half real time: no invented loss" '! grep -q "went missing\|samples (estimated) lost" "$work/half.log"'
check_py "half real time: the stream's report" -m checks.rtltcp_slow_sender "$work/half" 0.5

# A trickle: 2000 bytes every 0.49 s for 6 s, all within the 0.25 s the tuner settles.
start_background server "$python" -S "$server_py" "$work/sim/if_cu8.bin" --rate "$fs" --port-file "$work/port_trickle" \
  --pace 0.001 --buffer-bytes 2000 --stop-after 6 2> "$work/server_trickle.log"
LIMIT_S=20 EXIT_STATUS=1 expect_failure "a trickle at 1/1000 of real time" \
  "the stream runs at 0.001 of real time" "without a sample to process" "discarded while the tuner settles" -- \
  "$deepnav" run --input "rtltcp://127.0.0.1:$(port_from "$work/port_trickle")" --out "$work/trickle"
reap $server || true
check_json_each "$work/trickle/summary.json" \
  "trickle: summary error says nothing was processed" error contains '"without a sample to process"' \
  "trickle: slower than real time" stream.slower_than_real_time == true \
  "trickle: pace below 0.002" stream.pace_of_real_time '<' 0.002 \
  "trickle: bytes received" stream.bytes_received '>' 0

# The header, then the connection closed.
start_background server "$python" -S "$server_py" "$work/sim/if_cu8.bin" --rate "$fs" --port-file "$work/port_close" \
  --close-after-header 2> "$work/server_close.log"
LIMIT_S=20 EXIT_STATUS=1 expect_failure "header, then closed" \
  "the server closed the connection" "without a sample to process" -- \
  "$deepnav" -q run --input "rtltcp://127.0.0.1:$(port_from "$work/port_close")" --out "$work/closed"
reap $server || true
check_json_each "$work/closed/summary.json" \
  "closed: summary error" error contains '"without a sample to process"' \
  "closed: no byte after the header" stream.bytes_received == 0
check "closed: products written" '[[ -f $work/closed/pvt.csv ]]'
finish
