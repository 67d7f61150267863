#!/usr/bin/env bash
# `deepnav sim`: bad input gets a clear message naming the problem, a non-zero exit
# and no output file that looks complete; a tiny good run writes every product.
#   usage: sim_bad_input.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
base='start_time: "2022-01-01T02:00:00"
duration_s: 0.05
sample_rate_hz: 2046000'

# sim_refused NAME EXPECTED_MESSAGE_FRAGMENT SCENARIO_TEXT [OUT_DIR]: refused, naming the
# problem, and nothing but .partial files left in OUT_DIR.
sim_refused() {
  local name=$1 fragment=$2 text=$3 out=${4:-$work/out_$1}
  printf '%s\n' "$text" > "$work/$name.yaml"
  expect_failure "$name" "$fragment" -- "$deepnav" sim --scenario "$work/$name.yaml" --out "$out"
  if [[ $last_check == ok && -d $out ]]; then
    check "$name: no complete-looking file left in ${out##*/}" '! ls "$out" | grep -qv "\.partial$"'
  fi
}
sim_refused negative_duration "duration_s" 'start_time: "2022-01-01T02:00:00"
duration_s: -1'
sim_refused unknown_format "format" "$base
format: int12"
sim_refused js_out_of_range "js_db" "$base
jammers: [{type: cw, js_db: 200}]"
sim_refused missing_nav "nav_file" "$base
nav_file: no/such/file.22n"
sim_refused malformed_yaml "not valid YAML" "$base
cn0: {dbhz: 45"
printf 'not a navigation file\n' > "$work/bad.nav"
sim_refused malformed_nav "bad.nav" "$base
nav_file: $work/bad.nav"
touch "$work/blocker"
sim_refused unwritable_out "blocker" "$base" "$work/blocker/out"
expect_failure missing_scenario "none.yaml" -- "$deepnav" sim --scenario "$work/none.yaml" --out "$work/none"

# A good tiny run writes every product under its final name.
printf '%s\n' "$base" > "$work/good.yaml"
sim_scenario "$work/good.yaml" "$work/good"
for f in if_ibyte.bin truth.csv sat_truth.csv scenario.yaml synthesis.json; do
  check "good run: $f written" '[[ -s $work/good/$f ]]'
done
# 0.05 s of 2-byte samples at the scenario's rate.
check "good run: IF size" '[[ $(stat -c %s "$work/good/if_ibyte.bin") -eq $(($(sample_rate_of "$work/good") / 20 * 2)) ]]'
check "good run: no partial file left" '! ls "$work/good" | grep -q partial'
finish
