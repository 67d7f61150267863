#!/usr/bin/env bash
# The recorded-data path against the IF path on one synthetic scenario (no real data): the
# land circle with a tactical IMU is synthesized, run through the IF receiver in tight
# mode, and its products (obs.rnx, nav.rnx) with the scenario's imu.csv are fed to
# `deepnav fuse --mode tight`. Without carrier smoothing (the IF run has none) the two
# solutions agree within a few decimetres on every epoch both have in tight mode; with it
# (fuse's default) fuse is no further from the truth than the IF run. The receiver steers
# its time tags by microsecond steps, which the RINEX reader must find as clock re-sets.
#   usage: fuse_consistency.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$deepnav" -q sim --scenario "$src/data/scenarios/land_circle_aided_90s.yaml" --out "$work/sim" > /dev/null ||
  { echo "FAIL sim"; exit 1; }
"$deepnav" -q run --input "$work/sim/if_ibyte.bin" --fs 2600000 --week 2190 --mode tight --imu "$work/sim/imu.csv" \
  --imu-grade tactical --imu-grades-file "$src/data/imu_grades.yaml" --imu-lever-arm 0.8 -0.3 0.4 \
  --ephemeris-from "$src/data/brdc0010.22n" --iono-from "$src/data/brdc0010.22n" --truth "$work/sim/truth.csv" \
  --out "$work/if" > /dev/null || { echo "FAIL run tight"; exit 1; }
# The IMU's time is the IF file's sample time; the receiver's time tags are that plus a
# constant (to microseconds): the offset from the IF run's own pvt.csv.
offset=$(python3 -c "
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print('%.6f' % statistics.median(float(r['gps_sow']) - float(r['t_s']) for r in rows))" "$work/if/pvt.csv") ||
  { echo "FAIL no time offset"; exit 1; }
fuse() {  # fuse OUT [options]
  local out=$1
  shift
  "$deepnav" -q fuse --obs "$work/if/obs.rnx" --nav "$work/if/nav.rnx" --imu "$work/sim/imu.csv" --imu-format deepnav \
    --imu-time-base week-seconds --imu-time-offset "$offset" --imu-grade tactical \
    --imu-grades-file "$src/data/imu_grades.yaml" --imu-position 0.8 -0.3 0.4 --mode tight --out "$work/$out" "$@" \
    > /dev/null
}
fuse raw --no-smoothing || { echo "FAIL fuse --no-smoothing"; exit 1; }
fuse smoothed || { echo "FAIL fuse"; exit 1; }
python3 - "$work" "$offset" <<'PY'
import csv, json, math, sys
work, offset = sys.argv[1], float(sys.argv[2])

def ned(ref, d):
    lat, lon = math.radians(float(ref["lat_deg"])), math.radians(float(ref["lon_deg"]))
    n = -math.sin(lat) * math.cos(lon) * d[0] - math.sin(lat) * math.sin(lon) * d[1] + math.cos(lat) * d[2]
    e = -math.sin(lon) * d[0] + math.cos(lon) * d[1]
    u = math.cos(lat) * math.cos(lon) * d[0] + math.cos(lat) * math.sin(lon) * d[1] + math.sin(lat) * d[2]
    return n, e, u

def load(path):
    return {round(float(r["gps_sow"]), 3): r for r in csv.DictReader(open(path)) if r["mode"] == "tight"}

def diff(a, b):
    d = [float(b[k + "_ecef_m"]) - float(a[k + "_ecef_m"]) for k in "xyz"]
    return ned(a, d)

truth = {round(float(r["t_s"]), 3): r for r in csv.DictReader(open(f"{work}/sim/truth.csv"))}

def truth_rms(rows):
    # Epochs fall on whole seconds of sample time (to the microseconds of the time tags).
    h = [math.hypot(*diff(truth[float(round(t - offset))], r)[:2]) for t, r in rows.items()
         if float(round(t - offset)) in truth]
    return math.sqrt(sum(x * x for x in h) / len(h))

ifr, raw, smoothed = load(f"{work}/if/pvt.csv"), load(f"{work}/raw/pvt.csv"), load(f"{work}/smoothed/pvt.csv")
common = sorted(set(ifr) & set(raw))
d = [diff(ifr[t], raw[t]) for t in common]
h = [math.hypot(n, e) for n, e, _ in d]
d3 = [math.sqrt(n * n + e * e + u * u) for n, e, u in d]
s = json.load(open(f"{work}/raw/summary.json"))
jumps = len(s["observation_file"]["clock_jumps"])
rejected = s["fusion"]["rows_rejected"]
rms_if, rms_smoothed = truth_rms(ifr), truth_rms(smoothed)
print(f"{len(common)} epochs: fuse - IF horizontal RMS {math.sqrt(sum(x * x for x in h) / len(h)):.3f} m, "
      f"max {max(h):.3f} m, 3-D max {max(d3):.3f} m; clock re-sets found {jumps}, rows rejected {rejected}; "
      f"horizontal RMS against the truth: IF {rms_if:.3f} m, fuse smoothed {rms_smoothed:.3f} m")
bad = []
if len(common) < 70: bad.append(f"only {len(common)} common tight epochs")
if max(h) > 0.3: bad.append(f"horizontal difference {max(h):.3f} m > 0.3 m")
if max(d3) > 0.5: bad.append(f"3-D difference {max(d3):.3f} m > 0.5 m")
if jumps < 2: bad.append(f"{jumps} receiver clock re-sets found (the receiver steps its time tags)")
if rejected > 10: bad.append(f"{rejected} rows rejected")
if rms_smoothed > rms_if + 0.05: bad.append(f"smoothed fuse {rms_smoothed:.3f} m from the truth against the IF run's {rms_if:.3f} m")
print("FAIL " + "; ".join(bad) if bad else "PASS")
sys.exit(1 if bad else 0)
PY
