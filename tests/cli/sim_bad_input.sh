#!/usr/bin/env bash
# `deepnav sim`: bad input gets a clear message naming the problem, a non-zero exit
# and no output file that looks complete; a tiny good run writes every product.
#   usage: sim_bad_input.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

base='start_time: "2022-01-01T02:00:00"
duration_s: 0.05
sample_rate_hz: 2046000'

# expect_failure NAME EXPECTED_MESSAGE_FRAGMENT SCENARIO_TEXT [OUT_DIR]
expect_failure() {
  local name=$1 fragment=$2 text=$3 out=${4:-$work/out_$1}
  printf '%s\n' "$text" > "$work/$name.yaml"
  local msg
  msg=$("$deepnav" sim --scenario "$work/$name.yaml" --out "$out" 2>&1 >/dev/null)
  local rc=$?
  if [[ $rc -eq 0 ]]; then
    echo "FAIL $name: exit status 0"; failures=$((failures + 1)); return
  fi
  if [[ $msg != *"$fragment"* ]]; then
    echo "FAIL $name: message lacks '$fragment': $msg"; failures=$((failures + 1)); return
  fi
  if [[ -d $out ]] && ls "$out" | grep -qv '\.partial$'; then
    echo "FAIL $name: left files in $out: $(ls "$out")"; failures=$((failures + 1)); return
  fi
  echo "ok   $name: $msg"
}

expect_failure negative_duration "duration_s" 'start_time: "2022-01-01T02:00:00"
duration_s: -1'
expect_failure unknown_format "format" "$base
format: int12"
expect_failure js_out_of_range "js_db" "$base
jammers: [{type: cw, js_db: 200}]"
expect_failure missing_nav "nav_file" "$base
nav_file: no/such/file.22n"
expect_failure malformed_yaml "not valid YAML" "$base
cn0: {dbhz: 45"
printf 'not a navigation file\n' > "$work/bad.nav"
expect_failure malformed_nav "bad.nav" "$base
nav_file: $work/bad.nav"
touch "$work/blocker"
expect_failure unwritable_out "blocker" "$base" "$work/blocker/out"

# A scenario file that does not exist.
if "$deepnav" sim --scenario "$work/none.yaml" --out "$work/none" >/dev/null 2>&1; then
  echo "FAIL missing scenario accepted"; failures=$((failures + 1))
else
  echo "ok   missing_scenario"
fi

# A good tiny run writes every product under its final name.
printf '%s\n' "$base" > "$work/good.yaml"
if "$deepnav" sim --scenario "$work/good.yaml" --out "$work/good" >/dev/null; then
  for f in if_ibyte.bin truth.csv sat_truth.csv scenario.yaml synthesis.json; do
    [[ -s $work/good/$f ]] || { echo "FAIL good run lacks $f"; failures=$((failures + 1)); }
  done
  size=$(stat -c %s "$work/good/if_ibyte.bin")
  [[ $size -eq $((2046 * 50 * 2)) ]] || { echo "FAIL IF size $size"; failures=$((failures + 1)); }
  ls "$work/good" | grep -q partial && { echo "FAIL partial file left"; failures=$((failures + 1)); }
  echo "ok   good run"
else
  echo "FAIL good run failed"; failures=$((failures + 1))
fi
exit $((failures > 0))
