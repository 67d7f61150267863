#!/usr/bin/env bash
# Filter-guided reacquisition (data/scenarios/land_circle_weak_rising_60s.yaml): PRN 25 is
# blocked for the first 20 s and then received at 20 dB-Hz, well below what the FFT
# acquisition finds. In ultra-tight mode the filter predicts where its signal is, a narrow
# search with seconds of integration finds it after it rises and not before, and the
# channel started there, its bits and time taken from the prediction, is steered and
# measured by the filter within 10 s of the signal's return (eight satellites in the
# filter); the solution stays within 1.5 m. With --no-guided-reacquisition the satellite is
# never tracked (seven satellites throughout).
#   usage: guided_reacquisition.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$deepnav" -q sim --scenario "$src/data/scenarios/land_circle_weak_rising_60s.yaml" --out "$work/sim" > /dev/null || { echo "FAIL sim"; exit 1; }
run() {  # run OUT [options]
  local out=$1
  shift
  "$deepnav" -q run --input "$work/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 \
    --ephemeris-from "$src/data/brdc0010.22n" --iono-from "$src/data/brdc0010.22n" --truth "$work/sim/truth.csv" \
    --out "$work/$out" --mode ultra --imu "$work/sim/imu.csv" --imu-grade tactical \
    --imu-grades-file "$src/data/imu_grades.yaml" --imu-lever-arm 0.8 -0.3 0.4 "$@" > /dev/null || { echo "FAIL run $out"; exit 1; }
}
run guided
run unguided --no-guided-reacquisition
python3 - "$work" <<'PY'
import csv, json, sys
work = sys.argv[1]
rise = 20.0
bad = []
g = json.load(open(f"{work}/guided/summary.json"))
u = json.load(open(f"{work}/unguided/summary.json"))
searches = [s for s in g["guided_searches"] if s["prn"] == 25]
confirmed = [s for s in searches if s["outcome"] == "confirmed"]
early = [s for s in searches if s.get("detection") and s["ended_s"] < rise]
print("PRN 25 searches:", ", ".join(f"{s['started_s']:.0f}-{s['ended_s']:.0f} s {s['outcome']}" for s in searches))
if early:
    bad.append(f"a signal found while PRN 25 was blocked: {early}")
if not confirmed:
    bad.append("PRN 25 never found and confirmed")
else:
    c = confirmed[0]
    d = c["detection"]
    print(f"found {d['dwell_s']:.1f} s of integration, {d['cn0_dbhz']:.1f} dB-Hz, {d['code_offset_chips']:+.2f} chips, "
          f"{d['doppler_offset_hz']:+.1f} Hz from the prediction; confirmed at {c['ended_s']:.1f} s")
    if c["ended_s"] > rise + 10.0:
        bad.append(f"confirmed only at {c['ended_s']:.1f} s")
    if not 17.0 <= d["cn0_dbhz"] <= 23.0:
        bad.append(f"search C/N0 {d['cn0_dbhz']:.1f} dB-Hz for a 20 dB-Hz signal")
    if abs(d["code_offset_chips"]) > 0.25:
        bad.append(f"found {d['code_offset_chips']:+.2f} chips from a prediction good to metres")
if 25 in u["acquired_prns"] or u["guided_searches"]:
    bad.append(f"--no-guided-reacquisition: PRN 25 acquired or searched ({u['acquired_prns']}, {u['guided_searches']})")
def filter_satellites(out, t0):
    return [int(r["filter_satellites"]) for r in csv.DictReader(open(f"{work}/{out}/pvt.csv"))
            if float(r["t_s"]) >= t0 and r["mode"] == "ultra"]
after = filter_satellites("guided", rise + 10.0)
if not after or min(after) < 8:
    bad.append(f"guided: satellites in the filter after {rise + 10:.0f} s: {sorted(set(after))}, expected 8")
if max(filter_satellites("unguided", 0.0), default=0) > 7:
    bad.append("unguided: more than the seven tracked satellites in the filter")
for s in (g, u):
    if s["horizontal_error_m"]["max"] > 1.5:
        bad.append(f"horizontal error {s['horizontal_error_m']['max']:.2f} m")
print(f"horizontal error max guided {g['horizontal_error_m']['max']:.2f} m, unguided {u['horizontal_error_m']['max']:.2f} m")
print("\n".join(bad) if bad else "ok")
sys.exit(1 if bad else 0)
PY
