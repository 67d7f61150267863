#!/usr/bin/env bash
# Packed formats round trip: for each layout below a short static scenario is synthesized in
# that format (2-bit, 4-bit and 1-bit values; real and I/Q; two's complement, sign/magnitude
# and offset binary codes; the bit and word orders GNSS-SDR reads) and the receiver, given the
# same --format (the first layout) or only the metadata file the synthesizer wrote beside the
# samples (the others), and an assisted start, must fix from it within a few metres of the
# truth. A wrong packed name fails naming the token, and so does a packed format for a stream.
#   usage: format_packed.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
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
  sed -e 's/duration_s: 120/duration_s: 22/' -e "s/sample_rate_hz: 2600000/sample_rate_hz: $fs\nif_hz: $if_hz/" \
      -e "s/format: ibyte/format: $format/" -e "s/adc: {bits: 4, agc: true}/adc: {bits: $bits, agc: true}/" \
      "$src/data/scenarios/static_120s.yaml" > "$work/$format.yaml"
  if ! "$deepnav" -q sim --scenario "$work/$format.yaml" --out "$work/$format" > /dev/null; then
    echo "FAIL $format: sim"; failures=$((failures + 1)); continue
  fi
  file=$(ls "$work/$format"/if_*.bin)
  if [[ $format == two_bit_packed ]]; then
    source_options=(--input "$file" --format "$format" --fs "$fs" --if "$if_hz")
  else
    source_options=(--metadata "${file%.bin}.xml")
  fi
  if ! "$deepnav" -q run "${source_options[@]}" --week 2190 \
      --iono-from "$src/data/brdc0010.22n" --ephemeris-from "$src/data/brdc0010.22n" \
      --truth "$work/$format/truth.csv" --out "$work/$format/run" > /dev/null; then
    echo "FAIL $format: run"; failures=$((failures + 1)); continue
  fi
  python3 - "$work/$format/run/summary.json" "$format" "$(basename "$file")" <<'PY' || failures=$((failures + 1))
import json, sys
s = json.load(open(sys.argv[1]))
h = s["horizontal_error_m"]["rms"] if s["fixes"] else float("nan")
ok = s["fixes"] >= 4 and h <= 6.0
print(("ok  " if ok else "FAIL"), f"{sys.argv[2]:26s} {sys.argv[3]:34s} fixes {s['fixes']:3d}, horizontal RMS {h:.2f} m",
      "(flags)" if sys.argv[2] == "two_bit_packed" else "(metadata alone)")
sys.exit(0 if ok else 1)
PY
  [[ $format == packed2_iq ]] || rm -f "$file"
done
# The same bytes read in the wrong bit order are noise: no fix.
"$deepnav" -q run --input "$work/packed2_iq/if_packed2_iq.bin" --format packed2_iq_msb --fs 2048000 --week 2190 \
  --ephemeris-from "$src/data/brdc0010.22n" --out "$work/wrong" > /dev/null 2>&1
fixes=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["fixes"])' "$work/wrong/summary.json" 2>/dev/null)
if [[ $fixes == 0 ]]; then echo "ok   packed2_iq read as packed2_iq_msb: no fix"; else echo "FAIL wrong order gave fixes: $fixes"; failures=$((failures + 1)); fi
expect_error() {  # expect_error TEXT COMMAND...
  local text=$1 msg rc
  shift
  msg=$("$@" 2>&1)
  rc=$?
  if [[ $rc -eq 0 || $msg != *"$text"* ]]; then
    echo "FAIL $*: exit $rc, message: $msg"; failures=$((failures + 1))
  else
    echo "ok   exit $rc: $(head -1 <<< "$msg")"
  fi
}
touch "$work/empty.bin"
printf 'abcd' > "$work/four.bin"
expect_error "unknown token 'iqq'" "$deepnav" -q run --input "$work/four.bin" --format packed2_iqq --fs 4000000 --out "$work/bad"
expect_error "1, 2 or 4 bits" "$deepnav" -q run --input "$work/four.bin" --format packed3 --fs 4000000 --out "$work/bad"
expect_error "cannot be streamed" "$deepnav" -q serve --file "$work/four.bin" --format packed2 --fs 4000000 --tcp 0
expect_error "packed formats are read from files" "$deepnav" -q run --input tcp://127.0.0.1:9 --raw --format packed2_iq \
  --fs 4000000 --out "$work/bad"
exit $((failures > 0))
