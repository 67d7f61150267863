#!/usr/bin/env bash
# UDP with injected frame loss: `deepnav serve` never sends frames 5-7, 100 and 250; the
# receiver must report exactly those frames lost, and their samples as gaps at the right
# sample indices (4096 samples per 8192-byte ibyte frame), nothing else.
#   usage: stream_udp_loss.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
scenario=$src/data/scenarios/default.yaml
duration_s=3
start_background server "$deepnav" -q serve --scenario "$scenario" --duration $duration_s --udp 0 --pace 4 --sessions 1 \
  --udp-frame-bytes 8192 --drop-frames 5,6,7,100,250 --port-file "$work/ports"
port=$(port_from "$work/ports" udp)
run_receiver "$work/udp" --input "udp://127.0.0.1:$port" --week 2190
reap $server || fail "serve exit status"
n=4096  # samples in a frame of 8192 bytes, 2 a sample
total_frames=$((duration_s * $(scenario_value "$scenario" sample_rate_hz) / n + 1))
check_json_each "$work/udp/summary.json" \
  "lost frame ranges [5,7], [100,100], [250,250]" stream.lost_frame_ranges '==' '[[5, 7], [100, 100], [250, 250]]' \
  "5 frames lost" stream.frames_lost '==' 5 \
  "gaps at the dropped frames' samples" stream.gaps '==' \
  "[{\"first_missing_sample\": $((5 * n)), \"missing_samples\": $((3 * n))},
    {\"first_missing_sample\": $((100 * n)), \"missing_samples\": $n},
    {\"first_missing_sample\": $((250 * n)), \"missing_samples\": $n}]" \
  "lost samples = 5 frames" stream.lost_samples '==' $((5 * n)) \
  "no overrun frame" stream.frames_overrun '==' 0 \
  "no duplicated frame" stream.frames_duplicated '==' 0 \
  "no late frame" stream.frames_late '==' 0 \
  "all $total_frames frames but the 5 received" stream.frames_received '==' $((total_frames - 5)) \
  "ended normally" stream.end '==' '"end of stream"' \
  "the stream did not fail" stream.failed '==' false
finish
