#!/usr/bin/env bash
# Hostile or careless configuration and metadata files (the reproducers of tests/data/repro/
# and variants): each must end at once with a non-zero exit, a message naming the file, the
# line or element and what is wrong, and no output folder. They once crashed (a metadata
# file nested 50,000 deep), hung (an alias bomb), were read wrong without a word (a number
# truncated, a key given twice) or were refused with a message about something else. And a
# --skip into a packed word goes on reading past that word.
#   usage: parser_bad_input.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
repro=$src/tests/data/repro
cd "$work"  # the reproducers name their outputs relative to where they are run
head -c 409200 /dev/urandom > noise.bin  # 0.05 s ibyte at 4.092 Msps

# refused NAME FRAGMENT... -- ARGUMENTS: `deepnav -q ARGUMENTS` exits 1 within 10 s, its message
# holding every FRAGMENT, and leaves nothing in ./out (the output folder of every case here).
refused() {
  local name=$1 expected=()
  shift
  while [[ $1 != -- ]]; do expected+=("$1"); shift; done
  shift
  rm -rf out
  LIMIT_S=10 EXIT_STATUS=1 expect_failure "$name" "${expected[@]}" -- "$deepnav" -q "$@"
  check "$name: no output folder" '[[ ! -e out ]]'
}

# 1: the recursive XML parser overflowed its stack (SIGSEGV) on 50,000 nested elements.
{ printf '<?xml version="1.0"?>\n<metadata>\n'; printf '<a>%.0s' $(seq 50000); } > deep.xml
refused metadata_nested_50000_acquire "metadata file 'deep.xml':3: elements nested more than 64 deep" -- \
  acquire --metadata deep.xml
refused metadata_nested_50000_run "deep.xml':3: elements nested more than 64 deep" -- \
  run --metadata deep.xml --week 2190 --out out

# 2: the duplicate-key check followed every alias: 10^12 visits for 12 lines, in every reader.
refused alias_bomb_config "cfg_laughs.yaml:5: the aliases repeat more than 100000 nodes" -- \
  --config "$repro/cfg_laughs.yaml" run
refused alias_bomb_scenario "cfg_laughs.yaml:5: the aliases repeat more than 100000 nodes" -- \
  sim --scenario "$repro/cfg_laughs.yaml" --out out
printf 't_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps\n0.01,0,0,0,0,0,-0.098\n' > imu.csv
rm -rf out
LIMIT_S=10 EXIT_STATUS=1 expect_failure alias_bomb_imu_grades \
  "cfg_laughs.yaml:5: the aliases repeat more than 100000 nodes" -- \
  "$deepnav" -q run --input noise.bin --fs 4092000 --week 2190 --mode ultra --imu imu.csv \
  --imu-grades-file "$repro/cfg_laughs.yaml" --out out
check "alias_bomb_imu_grades: no product" '[[ -z $(ls -A out 2> /dev/null) ]]'
printf 'a: &a [1, *a]\n' > loop.yaml
refused alias_loop "loop.yaml:1: alias '*a' is inside the node it names" -- --config loop.yaml run

# 17: doppler_max and doppler-max set one option; the first won without a word.
refused key_twice_normalised \
  "cfg_dupnorm2.yaml:6: key 'doppler-max' sets option --doppler-max again (key 'doppler_max' on line 5 set it)" -- \
  --config "$repro/cfg_dupnorm2.yaml" run

# 18: 2^32 + 8 bits were read as 8.
refused metadata_quantization_2e32 "md_quant_huge.xml': <metadata/lane[IF]/block/chunk/lump/stream[L1]/quantization>:" \
  "4294967304 is too large: at most 64" -- acquire --metadata "$repro/md_quant_huge.xml"

# 23-31: messages about something else than what is wrong.
refused metadata_rate_1hz "md_freqbase_1hz.xml': <metadata/system[deepnav-sim]/freqbase>: sample rate 1 Hz" \
  "outside the 1000000 to 200000000 Hz" -- run --metadata "$repro/md_freqbase_1hz.xml" --week 2190 --out out
refused metadata_cycles_overflow "md_cycles_wrap.xml': <metadata/lane[IF]/block/cycles>: 9223372036854775808 cycles" \
  "overflows" -- acquire --metadata "$repro/md_cycles_wrap.xml"
refused metadata_utf16 "md_utf16.xml' is encoded in UTF-16: metadata files are read as UTF-8" -- \
  acquire --metadata "$repro/md_utf16.xml"
refused config_nul "cfg_nul.yaml:2: a NUL byte at column 17" -- --config "$repro/cfg_nul.yaml" run

# Issue item 2: a folder as the configuration; a list for a key of one value.
rm -rf out
LIMIT_S=10 expect_failure config_directory "--config: configuration file '$work' is a directory" -- \
  "$deepnav" -q --config "$work" run
printf 'input: noise.bin\nfs: 4092000\nweek: 2190\nout: [out]\n' > list.yaml
refused config_list_for_one_value "list.yaml:4: key 'out': expected one value, got a list" -- --config list.yaml run
printf 'input: noise.bin\nfs: 4092000\nweek: 2190\nout: out\nraw: [true, false]\n' > flag_list.yaml
refused config_list_for_a_flag "flag_list.yaml:5: key 'raw': expected one value, got a list" -- \
  --config flag_list.yaml run

# 35: a --skip one sample into a packed word left the first block the 7 samples after it,
# which the cold start judged ("not IF samples") and searched (finding nothing). The same
# satellites as without a skip, and no word about the first samples.
derive_scenario "$src/data/scenarios/static_120s.yaml" packed.yaml 'duration_s: 3' 'sample_rate_hz: 2048000' \
  'format: packed2_iq_w32le' 'adc: {bits: 2, agc: true}' --append 'if_hz: 0'
sim_scenario packed.yaml packed
# A first word of equal values: alone, the 7 samples after the skip looked like no IF samples.
printf '\0\0\0\0' | dd of=packed/if_packed2_iq_w32le.bin conv=notrunc status=none
packed_run=(--input packed/if_packed2_iq_w32le.bin --format packed2_iq_w32le --fs 2048000 --week "$(week_of packed)")
run_receiver whole "${packed_run[@]}"
run_receiver skipped "${packed_run[@]}" --skip 0.00000048828125  # one sample
check_json "packed, no skip: 6 or more satellites acquired" whole/summary.json 'len(acquired_prns)' '>=' 6
prns() { json_value "$1" acquired_prns | tr -d '[] ' | tr , '\n' | sort -n | paste -sd,; }
check "packed, --skip one sample into a word: the same satellites acquired ($(prns skipped/summary.json))" \
  '[[ $(prns whole/summary.json) == $(prns skipped/summary.json) ]]'
check "packed, --skip one sample: no warning about the first samples" '! grep -q "the first" skipped.log'
finish
