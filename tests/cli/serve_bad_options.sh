#!/usr/bin/env bash
# `deepnav serve` refuses at start what no client could use, naming the option: a sample
# rate that is not a number (once "needs --fs"), an IF beyond half the sample rate (once
# served, every client failing), and frames that do not hold whole samples or are mostly
# header (--frame-bytes 3 with cu8 once sent one 2-byte sample per 30-byte frame).
#   usage: serve_bad_options.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
head -c 40000 /dev/zero > "$work/if.bin"
serve=("$deepnav" -q serve --file "$work/if.bin" --tcp 0 --sessions 1)
LIMIT_S=10 expect_failure "--fs nan" "--fs" "'nan' is not a finite number" -- "${serve[@]}" --fs nan
LIMIT_S=10 expect_failure "--if beyond half the rate" \
  "--if 3000000 Hz: not below half the sample rate (--fs 4000000 Hz: |IF| < 2000000 Hz)" -- \
  "${serve[@]}" --fs 4000000 --if 3000000
LIMIT_S=10 expect_failure "cu8 frames of 3 bytes" --ordered "--frame-bytes 3:" "whole cu8 samples (2 bytes each)" \
  "1 sample in a 30-byte frame, 93 % of it the 28-byte header" "give a multiple of 2 from 1024" -- \
  "${serve[@]}" --format cu8 --fs 2048000 --frame-bytes 3 --pace 0
LIMIT_S=10 expect_failure "UDP frames of half a sample" "--udp-frame-bytes 4097:" "whole ibyte samples" -- \
  "$deepnav" -q serve --file "$work/if.bin" --fs 4000000 --udp 0 --udp-frame-bytes 4097
finish
