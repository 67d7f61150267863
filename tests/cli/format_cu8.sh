#!/usr/bin/env bash
# cu8 (unsigned 8-bit I/Q, zero at 127.5, as an RTL-SDR writes it) round trip: a static
# scenario is synthesized at 2.048 Msps with an 8-bit ADC into if_cu8.bin, and the receiver
# (assisted start) fixes from it within a few metres of the truth; run from the metadata file
# the synthesizer wrote beside it, and served over TCP (framed, as fast as read), it gives the
# same fixes. A misspelt format names the accepted ones and exits non-zero.
#   usage: format_cu8.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
derive_scenario "$src/data/scenarios/static_120s.yaml" "$work/s.yaml" 'duration_s: 24' 'sample_rate_hz: 2048000' \
  'format: cu8' 'adc: {bits: 8, agc: true}'
sim_scenario "$work/s.yaml" "$work/sim"
fs=$(sample_rate_of "$work/sim")
week=$(week_of "$work/sim")
if_file=$work/sim/if_cu8.bin
check "sim wrote if_cu8.bin" '[[ -s $if_file ]]'
duration=$(json_value "$work/sim/synthesis.json" duration_s)
check "if_cu8.bin is 2 bytes a sample" \
  '[[ $(stat -c %s "$if_file") -eq $(awk "BEGIN { printf \"%d\", 2 * $duration * $fs }") ]]'
run_on_sim "$work/sim" "$work/run" "${assisted[@]}" --truth "$work/sim/truth.csv"
check_json_each "$work/run/summary.json" "cu8: fixes >= 5" fixes '>=' 5 \
  "cu8: horizontal RMS <= 5 m" horizontal_error_m.rms '<=' 5.0
run_receiver "$work/meta" --metadata "$work/sim/if_cu8.xml" --week "$week" "${assisted[@]}"
check "cu8 from if_cu8.xml alone: pvt.csv identical to the flags run's" 'cmp -s "$work/run/pvt.csv" "$work/meta/pvt.csv"'
start_background server "$deepnav" -q serve --file "$if_file" --format cu8 --fs "$fs" --tcp 0 --pace 0 --sessions 1 \
  --port-file "$work/ports"
port=$(port_from "$work/ports" tcp)
run_receiver "$work/tcp" --input "tcp://127.0.0.1:$port" --week "$week" "${assisted[@]}"
reap $server || fail "serve exit status"
check "cu8 over tcp://: pvt.csv identical to the file run's" 'cmp -s "$work/run/pvt.csv" "$work/tcp/pvt.csv"'
expect_failure "--format cu9 names cu8" --ordered "cu9" "cu8" -- \
  "$deepnav" -q run --input "$if_file" --format cu9 --fs "$fs" --out "$work/bad"
finish
