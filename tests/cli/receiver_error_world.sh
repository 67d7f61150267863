#!/usr/bin/env bash
# The error world reaches the pseudoranges: the same static 30 s scenario synthesized in
# the `none` world (the receiver's own models are the truth) and in `suburban` (thin-shell
# ionosphere, site troposphere, broadcast orbit/clock errors, patch antenna, land-mobile
# multipath and blockage), run through the scalar receiver with its default models. The
# suburban run must show clearly larger position errors, and sat_truth.csv must carry the
# error budget (nonzero ionosphere residual, orbit and multipath columns; all zero in none).
#   usage: receiver_error_world.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for world in none suburban; do
  sed -e 's/duration_s: 120/duration_s: 30/' "$src/data/scenarios/static_120s.yaml" > "$work/$world.yaml"
  echo "errors: {preset: $world}" >> "$work/$world.yaml"
  "$deepnav" -q sim --scenario "$work/$world.yaml" --out "$work/sim_$world" > /dev/null || { echo "FAIL sim $world"; exit 1; }
  "$deepnav" -q run --input "$work/sim_$world/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 \
    --iono-from "$src/data/brdc0010.22n" --ephemeris-from "$src/data/brdc0010.22n" \
    --truth "$work/sim_$world/truth.csv" --out "$work/run_$world" > /dev/null || { echo "FAIL run $world"; exit 1; }
done
python3 - "$work" <<'PY'
import csv, json, sys
w = sys.argv[1]
summ = {k: json.load(open(f"{w}/run_{k}/summary.json")) for k in ("none", "suburban")}
def budget(world):
    rows = list(csv.DictReader(open(f"{w}/sim_{world}/sat_truth.csv")))
    def rms(f):
        v = [float(r[f]) for r in rows if r["transmitting"] == "1"]
        return (sum(x * x for x in v) / len(v)) ** 0.5
    iono_residual = [float(r["iono_m"]) - float(r["iono_broadcast_m"]) for r in rows if r["transmitting"] == "1"]
    return {"iono_residual": (sum(x * x for x in iono_residual) / len(iono_residual)) ** 0.5,
            "orbit": rms("orbit_m"), "clock": rms("sat_clock_error_m"), "multipath": rms("multipath_m")}
b_none, b_sub = budget("none"), budget("suburban")
h = {k: summ[k]["horizontal_error_m"]["rms"] for k in summ}
v = {k: summ[k]["vertical_error_m"]["rms"] for k in summ}
checks = [
    ("none: every error column zero", all(x == 0.0 for x in b_none.values()), b_none),
    ("suburban: ionosphere residual RMS >= 0.3 m", b_sub["iono_residual"] >= 0.3, b_sub["iono_residual"]),
    ("suburban: orbit and clock errors present", b_sub["orbit"] > 0.05 and b_sub["clock"] > 0.05, (b_sub["orbit"], b_sub["clock"])),
    ("suburban: multipath present", b_sub["multipath"] > 0.1, b_sub["multipath"]),
    ("suburban 3-D RMS error > none's + 0.5 m", (h["suburban"]**2 + v["suburban"]**2) ** 0.5 > (h["none"]**2 + v["none"]**2) ** 0.5 + 0.5, (h, v)),
]
bad = 0
for name, ok, value in checks:
    print(("ok  " if ok else "FAIL"), name, value)
    bad += not ok
sys.exit(1 if bad else 0)
PY
