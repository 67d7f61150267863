#!/usr/bin/env bash
# Four seconds of IMU data missing in ultra-tight mode: the run once said nothing, kept the
# label "ultra" and let the height drift to -319 m with no satellite. Now the gap is
# reported (log and summary.json), the INS stops across it (no solution labelled ultra or
# tight inside it) and restarts after it, and no published fix is far from the truth.
#   usage: aided_imu_gap.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL $*"; exit 1; }
sed -e 's/duration_s: 90/duration_s: 25/' "$src/data/scenarios/land_circle_aided_90s.yaml" > "$work/short.yaml"
"$deepnav" -q sim --scenario "$work/short.yaml" --out "$work/sim" > /dev/null || fail "sim"
awk -F, '!($1 + 0 > 12.0 && $1 + 0 < 16.0) || $1 !~ /^[0-9.]+$/' "$work/sim/imu.csv" > "$work/imu_gap.csv"
"$deepnav" run --input "$work/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 \
  --ephemeris-from "$src/data/brdc0010.22n" --iono-from "$src/data/brdc0010.22n" --truth "$work/sim/truth.csv" \
  --out "$work/ultra" --mode ultra --imu "$work/imu_gap.csv" --imu-grade tactical \
  --imu-grades-file "$src/data/imu_grades.yaml" --imu-lever-arm 0.8 -0.3 0.4 > /dev/null 2> "$work/log" ||
  fail "run: $(tail -3 "$work/log")"
grep -q "imu_gap.csv:[0-9]*: no IMU data from t = 1[12]\.[0-9]* s to 1[56]\.[0-9]* s" "$work/log" || fail "no gap warning: $(cat "$work/log")"
python3 - "$work" <<'PY'
import csv, json, math, sys
work = sys.argv[1]
s = json.load(open(f"{work}/ultra/summary.json"))
truth = {round(float(r["t_s"]), 3): r for r in csv.DictReader(open(f"{work}/sim/truth.csv"))}
rows = list(csv.DictReader(open(f"{work}/ultra/pvt.csv")))
bad = []
gaps = s.get("imu_gaps", [])
if len(gaps) != 1 or abs(gaps[0]["from_s"] - 12.0) > 0.02 or abs(gaps[0]["to_s"] - 16.0) > 0.02:
    bad.append(f"summary imu_gaps {gaps}")
inside = [r for r in rows if 12.1 <= float(r["t_s"]) < 16.0]
aided_inside = [r["t_s"] for r in inside if r["mode"] in ("ultra", "tight", "loose", "coast")]
if aided_inside:
    bad.append(f"aided solutions inside the IMU gap at t = {aided_inside[:5]}")
worst = 0.0
for r in rows:
    t = truth.get(round(float(r["t_s"]), 3))
    if t is None:
        continue
    worst = max(worst, math.dist([float(r[k + "_ecef_m"]) for k in "xyz"], [float(t[k + "_ecef_m"]) for k in "xyz"]))
if worst > 30.0:
    bad.append(f"a published fix {worst:.1f} m from the truth")
after = [r["mode"] for r in rows if float(r["t_s"]) >= 20.0]
if "ultra" not in after:
    bad.append(f"ultra-tight did not come back after the gap: modes {sorted(set(after))}")
print("\n".join("FAIL " + b for b in bad) if bad else
      f"ok: gap reported, {len(inside)} fixes inside it from the receiver alone, worst fix {worst:.1f} m off, ultra again from t = {min(float(r['t_s']) for r in rows if float(r['t_s']) >= 16 and r['mode'] == 'ultra'):.0f} s")
sys.exit(1 if bad else 0)
PY
