#!/usr/bin/env bash
# End-to-end: `deepnav bench align` and `deepnav bench leverarm` run, write JSON, and show
# the papers' findings; bad options are refused with a non-zero exit.
#   usage: bench_align_leverarm.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
"$deepnav" bench align --runs 1 --json "$work/align.json" > "$work/align.txt" || abort "bench align"
"$deepnav" bench leverarm --runs 2 --json "$work/leverarm.json" > "$work/leverarm.txt" || abort "bench leverarm"
check "align's table names the one-shot pitch error" 'grep -q "one-shot pitch error at 1 deg/h z-gyro" "$work/align.txt"'
check "leverarm's report has Table 1" 'grep -q "Table 1" "$work/leverarm.txt"'
check_py "the papers' findings" -m checks.bench_align_leverarm "$work/align.json" "$work/leverarm.json"
expect_failure "--runs 0 refused" "--runs" -- "$deepnav" bench leverarm --runs 0
finish
