#!/usr/bin/env bash
# `deepnav run --config FILE`: the file --print-config writes reproduces the flags' run
# byte for byte; flags on the command line win over the file; a misspelt key, a value of
# the wrong type, a choice not offered or a key that is not a name exits non-zero naming
# the file, line and key.
# Runs from a folder outside the project, in ultra-tight mode without --imu-grades-file:
# the default IMU grades resolve from any working directory.
#   usage: receiver_config_file.sh <deepnav binary> <source dir>
set -uo pipefail
source "$(dirname "$0")/lib/same_products.sh"
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
sed -e 's/duration_s: 90/duration_s: 24/' "$src/data/scenarios/land_circle_aided_90s.yaml" > s.yaml
"$deepnav" -q sim --scenario s.yaml --out sim > /dev/null || { echo "FAIL sim"; exit 1; }
flags=(--input sim/if_ibyte.bin --fs 2600000 --mode ultra --imu sim/imu.csv --imu-lever-arm 0.8 -0.3 0.4
       --ephemeris-from "$src/data/brdc0010.22n" --iono-from "$src/data/brdc0010.22n" --week 2190 --truth sim/truth.csv)
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
"$deepnav" -q run "${flags[@]}" --out flags > /dev/null || { echo "FAIL run with flags (ultra, default IMU grades)"; exit 1; }
grep -q '"ultra"' flags/summary.json || fail "the flags' run did not reach ultra-tight mode"
"$deepnav" -q run "${flags[@]}" --out from_file --print-config > run.yaml || fail "--print-config"
[[ -e from_file ]] && fail "--print-config ran the receiver (it made the output folder)"
grep -q '^imu-lever-arm: \[0.8, -0.3, 0.4\]$' run.yaml || fail "run.yaml lacks the lever arm: $(grep lever run.yaml)"
grep -q '^mode: ultra$' run.yaml || fail "run.yaml lacks the mode"
"$deepnav" -q run --config run.yaml > /dev/null || fail "run --config run.yaml"
for f in flags/*; do
  same_product "$f" "from_file/$(basename "$f")" || fail "--config run differs from the flags' run in $(basename "$f")"
done
[[ $(ls flags | wc -l) -eq $(ls from_file | wc -l) ]] || fail "the runs wrote different files"
# A flag on the command line wins over the file.
"$deepnav" -q run --config run.yaml --mode tight --out override > /dev/null || fail "run --config with --mode tight"
grep -q '"mode": "tight"' override/summary.json || fail "--mode on the command line did not win over the file"
expect_error() {  # expect_error FILE_CONTENT EXPECTED_MESSAGE_PART...
  local content=$1 msg rc
  shift
  printf '%s\n' "$content" > bad.yaml
  msg=$("$deepnav" -q run --config bad.yaml 2>&1)
  rc=$?
  for part in "$@"; do
    if [[ $rc -eq 0 || $msg != *"$part"* ]]; then fail "bad.yaml ($content): exit $rc, message: $msg"; return; fi
  done
  echo "ok   $(head -1 <<< "$msg")"
}
expect_error $'input: sim/if_ibyte.bin\nout: bad\nfs: 2600000\nimu-leverarm: [1, 2, 3]' \
  "bad.yaml:4:" "unknown key 'imu-leverarm'" "did you mean 'imu-lever-arm'"
expect_error $'input: sim/if_ibyte.bin\nout: bad\nfs: fast' "bad.yaml:3:" "'fs'" "not a number"
expect_error $'input: sim/if_ibyte.bin\nout: bad\nmode: ultrax' "bad.yaml:3:" "'mode'" "ultra"
expect_error $'input: sim/if_ibyte.bin\nout: bad\nimu-lever-arm: [1, 2]' "bad.yaml:3:" "expected 3"
expect_error $'input: sim/if_ibyte.bin\nout: bad\npll-order: {value: 3}' "bad.yaml:3:" "'pll-order'"
# Keys that are not names (found by fuzzing: yaml-cpp's "bad conversion", no file or line).
expect_error $'input: sim/if_ibyte.bin\n? [out, fs]\n: bad' "bad.yaml:2:" "expected an option name as the key" "list or a map"
expect_error $'? :' "bad.yaml:1:" "expected an option name as the key" "list or a map"
expect_error $'input: sim/if_ibyte.bin\n~: 3' "bad.yaml:2:" "expected an option name as the key" "null"
[[ -e bad ]] && fail "a rejected configuration made the output folder"
[[ $failures -eq 0 ]] && echo "ok   --config reproduces the flags' run; flags win; bad keys named"
exit $((failures > 0))
