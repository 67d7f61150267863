#!/usr/bin/env bash
# `deepnav run --config FILE`: the file --print-config writes reproduces the flags' run
# byte for byte; flags on the command line win over the file; a misspelt key, a value of
# the wrong type, a choice not offered or a key that is not a name exits non-zero naming
# the file, line and key.
# Runs from a folder outside the project, in ultra-tight mode without --imu-grades-file:
# the default IMU grades resolve from any working directory.
#   usage: receiver_config_file.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
cd "$work"
sim_scenario "$src/data/scenarios/land_circle_aided_90s.yaml" sim --duration 24
read -r _ lever_x lever_y lever_z <<< "$(py -m query imu sim/scenario.yaml)"
flags=(--input sim/if_ibyte.bin --fs "$(sample_rate_of sim)" --mode ultra --imu sim/imu.csv
       --imu-lever-arm "$lever_x" "$lever_y" "$lever_z" "${assisted[@]}" --week "$(week_of sim)" --truth sim/truth.csv)
run_receiver flags "${flags[@]}"
check "the flags' run reaches ultra-tight mode (ultra, default IMU grades)" 'grep -q "\"ultra\"" flags/summary.json'
"$deepnav" -q run "${flags[@]}" --out from_file --print-config > run.yaml || abort "--print-config"
check "--print-config does not run the receiver (no output folder)" '[[ ! -e from_file ]]'
check "run.yaml has the lever arm" "grep -q '^imu-lever-arm: \[$lever_x, $lever_y, $lever_z\]$' run.yaml"
check "run.yaml has the mode" "grep -q '^mode: ultra$' run.yaml"
"$deepnav" -q run --config run.yaml > from_file.log 2>&1 || abort "run --config run.yaml: $(cat from_file.log)"
check_same_products "--config run.yaml against the flags' run" flags from_file
# A flag on the command line wins over the file.
"$deepnav" -q run --config run.yaml --mode tight --out override > override.log 2>&1 ||
  abort "run --config with --mode tight: $(cat override.log)"
check "--mode on the command line wins over the file" 'grep -q "\"mode\": \"tight\"" override/summary.json'
expect_config_error() {  # FILE_CONTENT EXPECTED_MESSAGE_PART...
  local content=$1
  shift
  printf '%s\n' "$content" > bad.yaml
  expect_failure "bad.yaml ($content)" "$@" -- "$deepnav" -q run --config bad.yaml
}
expect_config_error $'input: sim/if_ibyte.bin\nout: bad\nfs: 2600000\nimu-leverarm: [1, 2, 3]' \
  "bad.yaml:4:" "unknown key 'imu-leverarm'" "did you mean 'imu-lever-arm'"
expect_config_error $'input: sim/if_ibyte.bin\nout: bad\nfs: fast' "bad.yaml:3:" "'fs'" "not a number"
expect_config_error $'input: sim/if_ibyte.bin\nout: bad\nmode: ultrax' "bad.yaml:3:" "'mode'" "ultra"
expect_config_error $'input: sim/if_ibyte.bin\nout: bad\nimu-lever-arm: [1, 2]' "bad.yaml:3:" "expected 3"
expect_config_error $'input: sim/if_ibyte.bin\nout: bad\npll-order: {value: 3}' "bad.yaml:3:" "'pll-order'"
# Keys that are not names (found by fuzzing: yaml-cpp's "bad conversion", no file or line).
expect_config_error $'input: sim/if_ibyte.bin\n? [out, fs]\n: bad' "bad.yaml:2:" "expected an option name as the key" \
  "list or a map"
expect_config_error $'? :' "bad.yaml:1:" "expected an option name as the key" "list or a map"
expect_config_error $'input: sim/if_ibyte.bin\n~: 3' "bad.yaml:2:" "expected an option name as the key" "null"
check "no rejected configuration made the output folder" '[[ ! -e bad ]]'
finish
