#!/usr/bin/env bash
# Packed formats round trip: for each layout below a short static scenario is synthesized in
# that format (2-bit, 4-bit and 1-bit values; real and I/Q; two's complement, sign/magnitude
# and offset binary codes; the bit and word orders GNSS-SDR reads) and the receiver, given the
# same --format (the first layout) or only the metadata file the synthesizer wrote beside the
# samples (the others), and an assisted start, must fix from it within a few metres of the
# truth. A wrong packed name fails naming the token, and so does a packed format for a stream.
#   usage: format_packed.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
# format  sample-rate  IF  ADC-bits
layouts=(
  "two_bit_packed 5000000 1250000 2"
  "packed2_iq 2048000 0 2"
  "two_bit_cpx 2048000 0 2"
  "packed2_iq_sm_msb 2048000 0 2"
  "packed2_sm_bytemsb_w16be 5000000 1250000 2"
  "packed2_qi_ob_w16le 2048000 0 2"
  "four_bit_cpx 2048000 0 4"
  "packed4_msb_w32be 5000000 1250000 4"
  "packed1_iq 2048000 0 1"
)
for layout in "${layouts[@]}"; do
  read -r format fs if_hz bits <<< "$layout"
  sim=$work/$format
  derive_scenario "$src/data/scenarios/static_120s.yaml" "$sim.yaml" 'duration_s: 22' "sample_rate_hz: $fs" \
    "format: $format" "adc: {bits: $bits, agc: true}" --append "if_hz: $if_hz"
  sim_scenario "$sim.yaml" "$sim"
  if [[ $format == two_bit_packed ]]; then
    run_receiver "$sim/run" --input "$sim/$(json_value "$sim/synthesis.json" if_file)" --format "$format" --fs "$fs" \
      --if "$if_hz" --week "$(week_of "$sim")" "${assisted[@]}" --truth "$sim/truth.csv"
    how="(flags)"
  else
    run_receiver "$sim/run" --metadata "$sim/$(json_value "$sim/synthesis.json" metadata_file)" --week "$(week_of "$sim")" \
      "${assisted[@]}" --truth "$sim/truth.csv"
    how="(metadata alone)"
  fi
  check_json_each "$sim/run/summary.json" "$format $how: fixes >= 4" fixes '>=' 4 \
    "$format $how: horizontal RMS <= 6 m" horizontal_error_m.rms '<=' 6.0
  [[ $format == packed2_iq ]] || rm -f "$sim"/if_*.bin
done
# The same bytes read in the wrong bit order are noise: no fix.
sim=$work/packed2_iq
"$deepnav" -q run --input "$sim/if_packed2_iq.bin" --format packed2_iq_msb --fs "$(sample_rate_of "$sim")" \
  --week "$(week_of "$sim")" --ephemeris-from "$brdc" --out "$work/wrong" > /dev/null 2>&1 || true
check_json "packed2_iq read as packed2_iq_msb: no fix" "$work/wrong/summary.json" fixes '==' 0
printf 'abcd' > "$work/four.bin"
expect_failure "packed2_iqq" "unknown token 'iqq'" -- \
  "$deepnav" -q run --input "$work/four.bin" --format packed2_iqq --fs 4000000 --out "$work/bad"
expect_failure "packed3" "1, 2 or 4 bits" -- \
  "$deepnav" -q run --input "$work/four.bin" --format packed3 --fs 4000000 --out "$work/bad"
expect_failure "serve packed2" "cannot be streamed" -- \
  "$deepnav" -q serve --file "$work/four.bin" --format packed2 --fs 4000000 --tcp 0
expect_failure "packed2_iq over tcp" "packed formats are read from files" -- \
  "$deepnav" -q run --input tcp://127.0.0.1:9 --raw --format packed2_iq --fs 4000000 --out "$work/bad"
finish
