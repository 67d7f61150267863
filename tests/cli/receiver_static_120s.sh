#!/usr/bin/env bash
# The receiver on a synthesized static 120 s scenario (8+ satellites at 45 dB-Hz):
# first fix within 40 s, horizontal RMS <= 3 m, vertical RMS <= 5 m, velocity RMS
# <= 0.05 m/s against the synthesizer's truth. Klobuchar parameters come from the
# navigation file until page 18 (every 12.5 min) is decoded.
#   usage: receiver_static_120s.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$deepnav" -q sim --scenario "$src/data/scenarios/static_120s.yaml" --out "$work/sim" > /dev/null || { echo "FAIL sim"; exit 1; }
"$deepnav" -q run --input "$work/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 \
  --iono-from "$src/data/brdc0010.22n" --truth "$work/sim/truth.csv" --out "$work/run" || { echo "FAIL run"; exit 1; }
python3 - "$work/run/summary.json" "$work/sim/synthesis.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
n_sats = len(json.load(open(sys.argv[2]))["satellites"])
checks = [
    ("satellites synthesized >= 8", n_sats >= 8, n_sats),
    ("time to first fix <= 40 s", s["time_to_first_fix_s"] is not None and s["time_to_first_fix_s"] <= 40.0, s["time_to_first_fix_s"]),
    ("horizontal RMS <= 3 m", s["horizontal_error_m"]["rms"] <= 3.0, s["horizontal_error_m"]["rms"]),
    ("vertical RMS <= 5 m", s["vertical_error_m"]["rms"] <= 5.0, s["vertical_error_m"]["rms"]),
    ("velocity RMS <= 0.05 m/s", s["velocity_error_mps"]["rms"] <= 0.05, s["velocity_error_mps"]["rms"]),
    ("a fix every epoch after the first", s["fixes"] >= s["epochs"] - 40, (s["fixes"], s["epochs"])),
]
bad = 0
for name, ok, value in checks:
    print(("ok  " if ok else "FAIL"), name, value)
    bad += not ok
sys.exit(1 if bad else 0)
PY
