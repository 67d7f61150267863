#!/usr/bin/env bash
# Inputs that once hung the program, exhausted its memory or were taken silently: each must
# now end within seconds with a non-zero exit and a message naming the file or option and
# the field (the reproducers of tests/data/repro/ and their variants).
#   usage: reliability_bad_input.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
repro=$src/tests/data/repro
head -c 4092000 /dev/urandom > "$work/noise.bin"  # 0.5 s ibyte at 4.092 Msps
printf 'this is a text file, not IF samples\n%.0s' $(seq 3000) > "$work/text.bin"

# refused NAME SECONDS FRAGMENT... -- ARGUMENTS: `deepnav -q ARGUMENTS` must exit non-zero
# within SECONDS, its message containing every FRAGMENT.
refused() {
  local name=$1 limit=$2 expected=()
  shift 2
  while [[ $1 != -- ]]; do expected+=("$1"); shift; done
  shift
  LIMIT_S=$limit expect_failure "$name" "${expected[@]}" -- "$deepnav" -q "$@"
}

scenario() {  # name, nav file, extra lines
  printf 'start_time: "2022-01-01T02:00:00"\nduration_s: 0.01\nsample_rate_hz: 2046000\nnav_file: %s\n%s\n' "$2" "${3:-}" \
    > "$work/$1.yaml"
}

# H1: the synthesizer spun forever on the range rate of one absurd navigation file field
# or of a trajectory that jumps; the files are refused where they are read.
scenario deltan "$repro/nav_prn2_deltan_1.23e19.22n"
refused h1_deltan 20 "nav_prn2_deltan_1.23e19.22n:10:" "PRN 2" "delta n = 1.23457e+19" -- \
  sim --scenario "$work/deltan.yaml" --out "$work/o1" --threads 1
scenario cuc "$repro/nav_prn5_cuc_1e29.22n"
refused h1_cuc 20 "nav_prn5_cuc_1e29.22n:11:" "PRN 5" "Cuc = 1e+29" -- \
  sim --scenario "$work/cuc.yaml" --out "$work/o1" --threads 1
scenario teleport "$brdc" "trajectory: {file: $repro/traj_teleport.csv}"
refused h1_teleport 20 "traj_teleport.csv:7: the position moves" -- \
  sim --scenario "$work/teleport.yaml" --out "$work/o1" --threads 1

# H5: a FIFO without a writer blocked forever in fopen.
mkfifo "$work/fifo"
refused h5_fifo 10 "sample file '$work/fifo' is a FIFO" -- run --input "$work/fifo" --fs 4092000 --week 2190 --out "$work/o5"

# H4: a thread that cannot be created deadlocked the pool's constructor. 1.5 GiB of address
# space cannot hold 255 thread stacks of 8 MiB. (Sanitizer builds reserve terabytes of
# address space and cannot run under a limit: skipped there.)
if ldd "$deepnav" 2>/dev/null | grep -q 'libasan\|libtsan'; then
  echo "skip h4_threads (sanitizer build)"
else
  ADDRESS_SPACE_KB=1500000 refused h4_threads 30 "cannot start channel worker thread" -- \
    run --input "$work/noise.bin" --fs 4092000 --week 2190 --out "$work/o4" --threads 256
fi
refused h4_thread_count 10 "--threads" "1000" -- \
  run --input "$work/noise.bin" --fs 4092000 --week 2190 --out "$work/o4" --threads 1000

# std::bad_alloc: a sample rate, a search length and a duration no memory holds, a device
# read as a scenario.
refused fs_1e12 10 "--fs" "1e12" -- run --input "$work/noise.bin" --fs 1e12 --week 2190 --out "$work/o6"
refused acquire_noncoherent 10 "--noncoherent" "1000000" -- \
  acquire --input "$work/noise.bin" --fs 4092000 --noncoherent 1000000
refused sim_duration_inf 10 "--duration" "inf" -- \
  sim --scenario "$src/data/scenarios/default.yaml" --out "$work/o7" --duration inf
refused sim_scenario_dev_zero 10 "scenario file '/dev/zero' is a device" -- sim --scenario /dev/zero --out "$work/o7"

# W6: option values outside what they can mean were taken (or ignored) silently.
run_noise=(run --input "$work/noise.bin" --fs 4092000 --week 2190 --out "$work/o8")
refused channels_0 10 "--channels" -- "${run_noise[@]}" --channels 0
refused if_nan 10 "--if" "nan" -- "${run_noise[@]}" --if nan
refused if_above_half_fs 10 "intermediate frequency 3000000 Hz is not below half the sample rate" -- \
  "${run_noise[@]}" --if 3e6
refused rate_1e-9 10 "--rate" -- "${run_noise[@]}" --rate 1e-9
refused lever_arm_nan 10 "--imu-lever-arm" "nan" -- "${run_noise[@]}" --imu-lever-arm 0 nan 0
refused reconnect_inf 10 "--reconnect-timeout" "inf" -- "${run_noise[@]}" --reconnect-timeout inf
refused sim_duration_negative 10 "--duration" "-5" -- \
  sim --scenario "$src/data/scenarios/default.yaml" --out "$work/o9" --duration -5

# W1: absurd weeks were accepted.
refused week_negative 10 "--week -1 is not a GPS week" -- \
  run --input "$work/noise.bin" --fs 4092000 --week -1 --out "$work/o10"
refused week_5000 10 "--week 5000 is not a GPS week" -- \
  run --input "$work/noise.bin" --fs 4092000 --week 5000 --out "$work/o10"

# W10: a text file "acquired" 10 satellites.
refused acquire_text 10 "text.bin: the I samples average" -- acquire --input "$work/text.bin" --fs 4092000

# C2: assistance files with one huge finite field failed later naming no file or satellite.
refused c2_af0 10 "nav_af0_1e300.22n:9: PRN 1" "af0 = 1e+300" -- \
  "${run_noise[@]}" --ephemeris-from "$repro/nav_af0_1e300.22n" --iono-from "$repro/nav_af0_1e300.22n"
refused c2_alpha 10 "nav_ion_alpha_1e301.22n:4: ION ALPHA: alpha0 = 1e+300" -- \
  "${run_noise[@]}" --iono-from "$repro/nav_ion_alpha_1e301.22n"
# W9: a RINEX epoch of Feb 31 (read as Mar 3) gave 512 m of error silently.
refused w9_feb31 10 "nav_epoch_feb31.22n:9: epoch line, day" "2022-02-31 is not a date" -- \
  "${run_noise[@]}" --ephemeris-from "$repro/nav_epoch_feb31.22n"

# C1/W2: one IMU sample beyond any sensor (dv 1e100 or 1e8 m/s in 10 ms).
{
  echo "# sample_rate_hz=100"
  echo "t_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps"
  for k in $(seq 1 50); do
    if [[ $k -eq 20 ]]; then echo "0.$(printf %02d $k),0,0,0,1e100,0,-0.098"; else echo "0.$(printf %02d $k),0,0,0,0,0,-0.098"; fi
  done
} > "$work/imu_spike.csv"
refused c1_imu_spike 10 "imu_spike.csv:22: column 'dv_x_mps': 1e+100 over 0.01 s" "beyond any accelerometer" -- \
  "${run_noise[@]}" --mode ultra --imu "$work/imu_spike.csv" --imu-grades-file "$imu_grades"

# M1/W4: a truth file with repeated column names read past a row; NaN and "123.4junk" passed.
refused m1_truth_duplicate 10 "truth_dup_header_oob.csv:1: column name 'a' appears twice" -- \
  "${run_noise[@]}" --truth "$repro/truth_dup_header_oob.csv"
printf 't_s,x_ecef_m,y_ecef_m,z_ecef_m,vx_ecef_mps,vy_ecef_mps,vz_ecef_mps\n0,1,2,3,4,5,6\n1,123.4junk,2,3,4,5,6\n' \
  > "$work/truth_junk.csv"
refused w4_truth_junk 10 "truth_junk.csv:3: column 'x_ecef_m': '123.4junk' is not a finite number" -- \
  "${run_noise[@]}" --truth "$work/truth_junk.csv"

# W8/W9/Y1: configuration and scenario files: another format, a repeated key, a missing
# field (yaml-cpp said "invalid node; first invalid key" naming no file).
refused w8_toml 10 "config_unknown_key.toml:1: expected a map of \`run\` options" -- \
  --config "$repro/config_unknown_key.toml" run
refused w8_toml_bom 10 "config_utf8_bom.toml:1: expected a map of \`run\` options" -- \
  --config "$repro/config_utf8_bom.toml" run
printf 'input: %s\nfs: 4092000\nfs: 2046000\nout: %s\n' "$work/noise.bin" "$work/o11" > "$work/dup.yaml"
refused w9_duplicate_key 10 "dup.yaml:3: key 'fs' appears twice in one mapping (lines 2 and 3)" -- \
  --config "$work/dup.yaml" run
printf '\xef\xbb\xbfinput: %s\nfs: 4092000\nout: %s\n' "$work/noise.bin" "$work/o11" > "$work/bom.yaml"
# The output is taken whole before it is searched: `grep -q` closing the pipe at its first
# match would end a slower (sanitizer) build's write with SIGPIPE, which pipefail reports.
bom_config=$("$deepnav" --config "$work/bom.yaml" run --print-config 2>&1) || true
check "w8_utf8_bom: a byte-order mark does not hide the first key ($(grep -m1 input <<< "$bom_config" || true))" \
  'grep -q "^input: $work/noise.bin" <<< "$bom_config"'
refused y1_jammer_type 10 "scenario_jammer_without_type.yaml:4: field 'jammers[0].type': missing required field" -- \
  sim --scenario "$repro/scenario_jammer_without_type.yaml" --out "$work/o12"
printf 'start_time: "2022-02-31T02:00:00"\nduration_s: 1\n' > "$work/feb31.yaml"
refused w9_start_feb31 10 "feb31.yaml:1: field 'start_time': '2022-02-31T02:00:00' is not a real date" -- \
  sim --scenario "$work/feb31.yaml" --out "$work/o12"
finish
