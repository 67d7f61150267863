#!/usr/bin/env bash
# Observables and fixes at 50 Hz (the fastest rate) with an assisted start: fixes every
# 20 ms once the clock is set, RINEX epochs at that interval, metre-level errors, and the
# summary's per-satellite navigation-data report; the same products with worker threads.
#   usage: receiver_50hz.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed -e 's/duration_s: 60/duration_s: 20/' "$src/data/scenarios/land_circle_60s.yaml" > "$work/s.yaml"
"$deepnav" -q sim --scenario "$work/s.yaml" --out "$work/sim" > /dev/null || { echo "FAIL sim"; exit 1; }
"$deepnav" -q run --input "$work/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 --rate 50 \
  --iono-from "$src/data/brdc0010.22n" --ephemeris-from "$src/data/brdc0010.22n" \
  --truth "$work/sim/truth.csv" --out "$work/run" > /dev/null || { echo "FAIL run"; exit 1; }
# Worker threads split the channels of each block: the products must not change.
"$deepnav" -q run --input "$work/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 --rate 50 \
  --iono-from "$src/data/brdc0010.22n" --ephemeris-from "$src/data/brdc0010.22n" --threads 3 \
  --out "$work/run_threads" > /dev/null || { echo "FAIL run --threads 3"; exit 1; }
for f in pvt.csv obs.rnx tracking.csv; do
  cmp -s "$work/run/$f" "$work/run_threads/$f" || { echo "FAIL $f differs with --threads 3"; exit 1; }
done
python3 - "$work" <<'PY'
import csv, json, sys
work = sys.argv[1]
bad = []
t = [float(r["t_s"]) for r in csv.DictReader(open(f"{work}/run/pvt.csv"))]
steps = {round(b - a, 4) for a, b in zip(t, t[1:])}
if len(t) < 50 * 5 or steps != {0.02}:
    bad.append(f"{len(t)} fixes, spacings {sorted(steps)[:5]}")
obs = open(f"{work}/run/obs.rnx").read()
if "     0.020 " not in obs.split("END OF HEADER")[0]:
    bad.append("RINEX INTERVAL is not 0.020")
epochs = obs.count("\n> ")
if epochs < 50 * 5:
    bad.append(f"only {epochs} RINEX epochs")
s = json.load(open(f"{work}/run/summary.json"))
if s["horizontal_error_m"] is None or s["horizontal_error_m"]["rms"] > 3.0:
    bad.append(f"horizontal error {s['horizontal_error_m']}")
nav = s.get("navigation", [])
if len(nav) < 4 or any(n["parity_failures"] < 0 or n["tracked_s"] <= 0 for n in nav):
    bad.append(f"navigation report {nav}")
print("\n".join(bad) if bad else f"ok: {len(t)} fixes at 50 Hz, {epochs} RINEX epochs, horizontal RMS {s['horizontal_error_m']['rms']:.2f} m")
sys.exit(1 if bad else 0)
PY
