#!/usr/bin/env bash
# Frames whose sequence number or sample index lie beyond what the stream's header allows:
# a UDP frame numbered 2^63 (its loss accounting once looped 9e18 times, and the process
# never exited), frames whose index jumps by 1e15 samples over UDP (a hang) and TCP
# (std::bad_alloc, no products). Each run must end within seconds with exit status 1, a
# message naming the stream and the field, and the products written up to there.
#   usage: stream_bad_frames.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
stream=$peers/bad_frame_stream.py

# ended_naming NAME OUT_DIR FRAGMENT -- COMMAND...: exit status 1 within 20 s naming
# FRAGMENT, with pvt.csv and a summary.json whose error names it too.
ended_naming() {
  local name=$1 out=$2 fragment=$3
  shift 4
  LIMIT_S=20 EXIT_STATUS=1 expect_failure "$name" "$fragment" -- "$@"
  if [[ $last_check == ok ]]; then
    check "$name: products written up to the error" '[[ -f $out/summary.json && -f $out/pvt.csv ]]'
    check_json "$name: summary.json's error names the reason" "$out/summary.json" error contains "\"$fragment\""
  fi
}

for mode in seqjump idxjump; do
  port=$(py "$stream" free-udp-port)
  start_background sender "$python" -S "$stream" udp $mode "$port"
  if [[ $mode == seqjump ]]; then
    fragment="sequence number 9223372036854775808 is beyond what its first sample index 1000000 allows"
  else
    fragment="first sample index 1000000000819200 is beyond what its sequence number allows"
  fi
  ended_naming "udp_$mode" "$work/udp_$mode" "$fragment" -- \
    "$deepnav" -q run --input "udp://@127.0.0.1:$port" --week 2190 --out "$work/udp_$mode"
  kill $sender 2>/dev/null || true
  reap $sender || true
done

start_background sender "$python" -S "$stream" tcp idxjump "$work/port"
ended_naming tcp_idxjump "$work/tcp_idxjump" "first sample index 1000000000819200 is beyond what its sequence number allows" -- \
  "$deepnav" -q run --input "tcp://127.0.0.1:$(port_from "$work/port")" --week 2190 --reconnect-timeout 1 \
  --out "$work/tcp_idxjump"
kill $sender 2>/dev/null || true
reap $sender || true
finish
