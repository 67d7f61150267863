#!/usr/bin/env bash
# Filter-guided reacquisition over seeds and C/N0: data/scenarios/land_circle_weak_rising_60s.yaml
# with PRN 25 at each C/N0 after its 20 s blockage, each seed a new noise, clock and IMU
# draw; ultra-tight with assisted ephemerides. Prints a Markdown table (and writes it to
# OUT/guided.md): when PRN 25 was found and locked by the filter after it rose, the search's
# C/N0 and offsets, and the horizontal error max. Points already run in OUT are kept.
#   usage: scripts/guided_reacquisition_sweep.sh DEEPNAV OUT [CN0S] [SEEDS]
#   e.g.   scripts/guided_reacquisition_sweep.sh build/tools/deepnav results/guided "16 18 20" "1 2 3"
set -euo pipefail
deepnav=$1
out=$2
cn0s=${3:-16 18 20}
seeds=${4:-1 2 3}
src=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
for cn0 in $cn0s; do
  for seed in $seeds; do
    point="$out/cn0_${cn0}_s${seed}"
    [ -f "$point/run/summary.json" ] && continue
    mkdir -p "$point"
    sed -e "s/per_prn: {25: 20}/per_prn: {25: $cn0}/" -e "s/^seed: .*/seed: $seed/" \
      "$src/data/scenarios/land_circle_weak_rising_60s.yaml" > "$point/scenario.yaml"
    echo "C/N0 $cn0 dB-Hz, seed $seed" >&2
    "$deepnav" -q sim --scenario "$point/scenario.yaml" --out "$point/sim" > /dev/null
    "$deepnav" -q run --input "$point/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 \
      --ephemeris-from "$src/data/brdc0010.22n" --iono-from "$src/data/brdc0010.22n" --truth "$point/sim/truth.csv" \
      --out "$point/run.tmp" --mode ultra --imu "$point/sim/imu.csv" --imu-grade tactical \
      --imu-grades-file "$src/data/imu_grades.yaml" --imu-lever-arm 0.8 -0.3 0.4 > /dev/null
    rm -rf "$point/sim" "$point/run"
    mv "$point/run.tmp" "$point/run"
    # Keep what the table needs; the IF file and the other products are large.
    find "$point/run" -type f ! -name summary.json ! -name pvt.csv -delete
  done
done
python3 - "$out" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
rise = 20.0
rows = []
for d in sorted(glob.glob(f"{out}/cn0_*_s*/run/summary.json")):
    name = d.split("/")[-3]
    cn0, seed = name[4:].split("_s")
    s = json.load(open(d))
    g = [x for x in s["guided_searches"] if x["prn"] == 25]
    early = [x for x in g if x.get("detection") and x["ended_s"] < rise]
    c = next((x for x in g if x["outcome"] == "confirmed"), None)
    found = c["ended_s"] - 1.0 if c else None
    rows.append((float(cn0), int(seed), len(g), len(early), c, s["horizontal_error_m"]["max"]))
lines = ["| PRN 25 C/N0 (dB-Hz) | seed | searches | detections while blocked | locked at (s) | after rising (s) | "
         "search dwell (s) | search C/N0 (dB-Hz) | code offset (chip) | Doppler offset (Hz) | horizontal error max (m) |",
         "|---|---|---|---|---|---|---|---|---|---|---|"]
for cn0, seed, n, early, c, hmax in sorted(rows):
    if c:
        d = c["detection"]
        lines.append(f"| {cn0:g} | {seed} | {n} | {early} | {c['ended_s']:.1f} | {c['ended_s'] - rise:.1f} | "
                     f"{d['dwell_s']:.1f} | {d['cn0_dbhz']:.1f} | {d['code_offset_chips']:+.2f} | "
                     f"{d['doppler_offset_hz']:+.1f} | {hmax:.2f} |")
    else:
        lines.append(f"| {cn0:g} | {seed} | {n} | {early} | not locked | | | | | | {hmax:.2f} |")
text = "\n".join(lines) + "\n"
open(f"{out}/guided.md", "w").write(text)
print(text, end="")
PY
