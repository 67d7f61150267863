#!/usr/bin/env bash
# ION GNSS SDR metadata files configure the source with no other flags: the real captures in
# data/ are acquired from their .xml alone (same PRNs as with the flags), the receiver runs
# on one; `deepnav sim` writes an .xml beside its IF file for every whole-byte format
# (ibyte, ishort, gr_complex, byte) and `deepnav run --metadata` alone fixes from each
# (cli.format_cu8 and cli.format_packed do the same for cu8 and the packed layouts). Broken
# or unsupported metadata exits non-zero naming the file and the element.
#   usage: metadata_run.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"

# The real captures.
for capture in L1_20211202_084700_4MHz_IQ L1_20211125_004000_12MHz_I; do
  "$deepnav" -q acquire --metadata "$src/data/$capture.xml" --json "$work/$capture.json" > /dev/null ||
    abort "acquire --metadata $capture.xml"
  check_py "$capture acquired from its metadata alone" -m checks.acquisition "$work/$capture.json" "$capture"
done
# 500 ms: --rate 4 makes two observation epochs (at --rate 1 it would hold none, exit 3).
run_receiver "$work/real" --metadata "$src/data/L1_20211202_084700_4MHz_IQ.xml" --rate 4
check_json "run --metadata on the 4 MHz capture acquires 5 or more" "$work/real/summary.json" 'len(acquired_prns)' '>=' 5

# Whole-byte formats synthesized and fixed from the metadata the synthesizer wrote.
for layout in "ibyte 2048000 0 4" "ishort 2048000 0 12" "gr_complex 2048000 0 0" "byte 5000000 1250000 4"; do
  read -r format fs if_hz bits <<< "$layout"
  sim=$work/$format
  derive_scenario "$src/data/scenarios/static_120s.yaml" "$sim.yaml" 'duration_s: 22' "sample_rate_hz: $fs" \
    "format: $format" "adc: {bits: $bits, agc: true}" --append "if_hz: $if_hz"
  sim_scenario "$sim.yaml" "$sim"
  xml=$sim/if_$format.xml
  check "$format: sim wrote ${xml##*/}" '[[ -s $xml ]]'
  # From another folder: the metadata names its file relative to itself.
  (cd "$work" && run_receiver "$sim/run" --metadata "$xml" --week "$(week_of "$sim")" "${assisted[@]}" \
    --truth "$sim/truth.csv")
  check_json_each "$sim/run/summary.json" "$format run --metadata alone: fixes >= 4" fixes '>=' 4 \
    "$format run --metadata alone: horizontal RMS <= 6 m" horizontal_error_m.rms '<=' 6.0
  rm -f "$sim"/if_*.bin
done

# Bad metadata: non-zero exit, the file and the element named.
good=$src/data/L1_20211202_084700_4MHz_IQ.xml
sed 's#</lane>#<lane#' "$good" > "$work/broken.xml"
expect_failure "broken XML" "broken.xml" "not well-formed XML" -- "$deepnav" -q acquire --metadata "$work/broken.xml"
sed 's#<encoding>INT8</encoding>#<encoding>OG</encoding>#' "$good" > "$work/og.xml"
expect_failure "unsupported encoding" "og.xml" "stream[L1]/encoding>" "'OG'" -- \
  "$deepnav" -q run --metadata "$work/og.xml" --out "$work/bad"
sed 's#<lump>#<lump><stream id="L2"/>#' "$good" > "$work/two.xml"
expect_failure "two streams" "two.xml" "lump/stream[L1]>" "2 <stream> elements" -- \
  "$deepnav" -q acquire --metadata "$work/two.xml"
sed 's#<url>L1_20211202_084700_4MHz_IQ.bin</url>#<url>missing.bin</url>#' "$good" > "$work/missing.xml"
expect_failure "missing sample file" "missing.xml" "missing.bin" "does not exist" -- \
  "$deepnav" -q acquire --metadata "$work/missing.xml"
expect_failure "metadata for a stream" "--metadata describes files" -- \
  "$deepnav" -q run --input tcp://127.0.0.1:9 --metadata "$good" --out "$work/bad"
finish
