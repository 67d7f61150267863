#!/usr/bin/env bash
# Paper 003's land circle through the receiver: every synthesized satellite is tracked
# from the start to the end of the run (never lost), and the fixes follow the circle.
#   usage: receiver_land_circle.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$deepnav" -q sim --scenario "$src/data/scenarios/land_circle_60s.yaml" --out "$work/sim" > /dev/null || { echo "FAIL sim"; exit 1; }
"$deepnav" -q run --input "$work/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 \
  --iono-from "$src/data/brdc0010.22n" --truth "$work/sim/truth.csv" --out "$work/run" || { echo "FAIL run"; exit 1; }
python3 - "$work" <<'PY'
import csv, json, sys
work = sys.argv[1]
synth = sorted(s["prn"] for s in json.load(open(f"{work}/sim/synthesis.json"))["satellites"])
first, last, states = {}, {}, {}
for r in csv.DictReader(open(f"{work}/run/tracking.csv")):
    p, t = int(r["prn"]), int(r["first_sample"]) / 2.6e6
    first.setdefault(p, t)
    last[p] = t
    states[p] = r["state"]
bad = []
for p in synth:
    if p not in first:
        bad.append(f"PRN {p} never tracked")
    elif first[p] > 0.1 or last[p] < 59.9 or states[p] != "2":
        bad.append(f"PRN {p} tracked {first[p]:.2f}-{last[p]:.2f} s, final state {states[p]}")
s = json.load(open(f"{work}/run/summary.json"))
if s["horizontal_error_m"] is None or s["horizontal_error_m"]["rms"] > 3.0:
    bad.append(f"horizontal error {s['horizontal_error_m']}")
print("\n".join(bad) if bad else f"ok: {len(synth)} satellites tracked for the whole run, horizontal RMS {s['horizontal_error_m']['rms']:.2f} m")
sys.exit(1 if bad else 0)
PY
