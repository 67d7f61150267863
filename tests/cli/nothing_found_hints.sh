#!/usr/bin/env bash
# Everyday mistakes get a hint, not a silent empty run: a wrong --fs, --if, --format, a
# missing --inverted-spectrum, a file too short for one epoch, a flag given over a metadata
# file's value. Each run exits 3 (nothing found) naming the likely cause with what was seen,
# and its summary.json says why in `nothing_found` (the other products are still written);
# `acquire` says the same, in its --json too. A right run still exits 0 without the field.
#   usage: nothing_found_hints.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
capture=$src/data/L1_20211202_084700_4MHz_IQ.bin  # inverted spectrum, IF 0, 4 Msps, 500 ms
metadata=$src/data/L1_20211202_084700_4MHz_IQ.xml

# nothing_found NAME OUT FRAGMENT... -- RUN_OPTIONS: `run --out OUT` exits 3 with every
# FRAGMENT in its message, and leaves summary.json (with nothing_found) and pvt.csv.
nothing_found() {
  local name=$1 out=$2 fragments=()
  shift 2
  while [[ $1 != -- ]]; do fragments+=("$1"); shift; done
  shift
  EXIT_STATUS=3 LIMIT_S=20 expect_failure "$name" "${fragments[@]}" -- "$deepnav" -q run --out "$out" "$@"
  check "$name: summary.json and pvt.csv written" '[[ -s $out/summary.json && -e $out/pvt.csv ]]'
}

# A short synthesized recording: 3 s, 2.048 Msps, 4-bit ibyte, white noise (no band).
derive_scenario "$src/data/scenarios/static_120s.yaml" "$work/s.yaml" 'duration_s: 3' 'sample_rate_hz: 2048000'
sim_scenario "$work/s.yaml" "$work/sim"
if_file=$work/sim/if_ibyte.bin
run_receiver "$work/right" --input "$if_file" --format ibyte --fs 2048000
check_json_each "$work/right/summary.json" "right settings: satellites acquired" 'len(acquired_prns)' '>=' 4 \
  "right settings: no nothing_found" . lacks '"nothing_found"'

nothing_found "wrong --fs" "$work/fs" "no satellite found in 2.5 s of signal" \
  "no correlation came near the threshold: --fs 2500000" -- --input "$if_file" --format ibyte --fs 2500000
check_json_each "$work/fs/summary.json" \
  "wrong --fs: reason" nothing_found.reason == '"no_satellite_acquired"' \
  "wrong --fs: sample rate suspected" nothing_found.suspects contains '"sample_rate"' \
  "wrong --fs: strongest correlation below the threshold" nothing_found.seen.strongest_correlation.ratio '<' 1 \
  "wrong --fs: the settings seen" nothing_found.seen.settings.sample_rate_hz == 2500000

nothing_found "wrong --if (white noise)" "$work/if_sim" "no satellite found in 3.0 s of signal" "--if 1000000" \
  "a flat spectrum" -- --input "$if_file" --format ibyte --fs 2048000 --if 1000000
check_json_each "$work/if_sim/summary.json" \
  "wrong --if (white noise): no band" nothing_found.seen.spectrum.band_found == false \
  "wrong --if (white noise): IF suspected" nothing_found.suspects contains '"intermediate_frequency"'

nothing_found "wrong --format" "$work/format" "pairs of 8-bit values read as one? (--format ishort)" -- \
  --input "$if_file" --format ishort --fs 2048000
check_json_each "$work/format/summary.json" \
  "wrong --format: format the one suspect" nothing_found.suspects == '["format"]' \
  "wrong --format: few low bytes seen" nothing_found.seen.low_byte_levels '<=' 16

# The real capture: its front end's filter makes a band, centred on the true IF (0).
nothing_found "wrong --if by 1 MHz (real capture)" "$work/if_real" "no satellite found in 500 ms of signal" \
  "the spectrum's centre is 1.00 MHz below --if 1000000: is the IF 0 Hz (complex baseband)?" -- \
  --input "$capture" --format ibyte --fs 4000000 --inverted-spectrum --if 1000000 --rate 4
check_json_each "$work/if_real/summary.json" \
  "wrong --if (real capture): IF the one suspect" nothing_found.suspects == '["intermediate_frequency"]' \
  "wrong --if (real capture): band 1 MHz below" nothing_found.seen.spectrum.offset_from_if_hz '<' -950000 \
  "wrong --if (real capture): not 1.05 MHz below" nothing_found.seen.spectrum.offset_from_if_hz '>' -1050000

# An inverted front end at IF +1 MHz: the capture moved down by fs/4.
py -m capture_edit down-quarter-rate "$capture" "$work/inverted_1mhz.bin" --fs 4000000 --ms 200
nothing_found "missing --inverted-spectrum" "$work/inverted" "with the spectrum inverted, acquisition finds PRN" \
  "add --inverted-spectrum" -- --input "$work/inverted_1mhz.bin" --format ibyte --fs 4000000 --if 1000000 --rate 10
check_json_each "$work/inverted/summary.json" \
  "missing --inverted-spectrum: the one suspect" nothing_found.suspects == '["spectrum_sense"]' \
  "missing --inverted-spectrum: PRN 31 found turned over" nothing_found.seen.inverted_spectrum_search.detected_prns \
  contains 31
run_receiver "$work/inverted_right" --input "$work/inverted_1mhz.bin" --format ibyte --fs 4000000 --if 1000000 \
  --rate 10 --inverted-spectrum
check_json "with --inverted-spectrum the same file acquires 5 or more" "$work/inverted_right/summary.json" \
  'len(acquired_prns)' '>=' 5

# Too short: the 500 ms capture at --rate 1, and its first 5 ms.
nothing_found "shorter than one epoch" "$work/short" "only 500.0 ms of signal: one observation epoch at --rate 1 needs 1000.0 ms" -- \
  --input "$capture" --format ibyte --fs 4000000 --inverted-spectrum
check_json_each "$work/short/summary.json" "too short: reason" nothing_found.reason == '"too_short"' \
  "too short: what it holds" nothing_found.seen.signal_ms == 500 \
  "too short: satellites were acquired all the same" 'len(acquired_prns)' '>=' 5
head -c 40000 "$capture" > "$work/5ms.bin"
nothing_found "5 ms" "$work/short5" "only 5.0 ms of signal: one observation epoch at --rate 1 needs 1000.0 ms" -- \
  --input "$work/5ms.bin" --format ibyte --fs 4000000 --inverted-spectrum
head -c 4000 "$capture" > "$work/halfms.bin"
EXIT_STATUS=3 expect_failure "acquire: shorter than one coherent block" \
  "only 0.5 ms of signal: one coherent block of --coherent-ms needs 1.0 ms" -- \
  "$deepnav" -q acquire --input "$work/halfms.bin" --format ibyte --fs 4000000

# --fs given over the metadata's rate: the hint names the flag, not "check the metadata file".
nothing_found "--fs over the metadata" "$work/over" "--fs 2500000 overrode $metadata's 4000000" \
  "is the metadata right after all?" -- --metadata "$metadata" --fs 2500000 --rate 4
check_json_each "$work/over/summary.json" "--fs over the metadata: suspect" nothing_found.suspects == '["sample_rate"]' \
  "--fs over the metadata: the value it replaced" 'nothing_found.seen.settings.overridden.--fs' == '"4000000"'

# acquire: the same diagnosis, exit 3, and in its --json.
EXIT_STATUS=3 expect_failure "acquire: wrong --if" "no satellite found in 10 ms of signal" \
  "MHz below --if 1000000: is the IF 0 Hz (complex baseband)?" -- \
  "$deepnav" -q acquire --input "$capture" --format ibyte --fs 4000000 --inverted-spectrum --if 1000000 \
  --json "$work/acq.json"
check_json_each "$work/acq.json" "acquire --json: nothing_found" nothing_found.reason == '"no_satellite_acquired"' \
  "acquire --json: every PRN still listed" 'len(results)' == 32
finish
