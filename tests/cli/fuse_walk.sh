#!/usr/bin/env bash
# deepnav fuse on the real walk (data/walk_0827) from another working directory through
# its configuration file, scored against the RTK reference; and bad inputs fail naming
# the file and the line.
#   usage: fuse_walk.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
"$deepnav" -q fuse --config "$src/data/walk_0827/walk.yaml" --mode tight --out tight \
  --compare "$src/results/fuse/rtklib_spp.pos" > tight.txt || { echo "FAIL fuse tight"; cat tight.txt; exit 1; }
for f in pvt.csv fixes.nmea track.kml track.gpx obs.rnx nav.rnx summary.json; do
  [ -s "tight/$f" ] || { echo "FAIL no tight/$f"; exit 1; }
done
python3 - "$work" <<'PY' || exit 1
import json, sys
s = json.load(open(f"{sys.argv[1]}/tight/summary.json"))
ours = s["reference_errors"]["about_mean_offset"]["rms_horizontal_m"]
spp = s["compare_errors"]["about_mean_offset"]["rms_horizontal_m"]
print(f"tight scatter {ours} m, RTKLIB single point {spp} m")
bad = []
if s["imu_log"]["duplicate_rows"] != 6958: bad.append(f"duplicate rows {s['imu_log']['duplicate_rows']}")
if s["observation_file"]["skipped_satellite_records"].get("E", 0) == 0: bad.append("Galileo records not counted")
if ours > spp + 0.05: bad.append(f"tight scatter {ours} m worse than single point {spp} m")
if bad:
    print("FAIL " + "; ".join(bad)); sys.exit(1)
PY
# Bad inputs: a truncated observation file, an IMU log with a bad value.
head -c 20000 "$src/data/walk_0827/walk.obs" > cut.obs
printf '0,0,1,0,0,0,1000\n0,0,1,x,0,0,1010\n0,0,1,0,0,0,1020\n' > bad_imu.csv
if "$deepnav" -q fuse --config "$src/data/walk_0827/walk.yaml" --obs cut.obs --out bad 2> err.txt; then
  echo "FAIL truncated observation file accepted"; exit 1; fi
grep -q "cut.obs:[0-9]*:" err.txt || { echo "FAIL no file:line in: $(cat err.txt)"; exit 1; }
if "$deepnav" -q fuse --config "$src/data/walk_0827/walk.yaml" --imu bad_imu.csv --out bad 2> err.txt; then
  echo "FAIL bad IMU log accepted"; exit 1; fi
grep -q "bad_imu.csv:2: column 4 (gx)" err.txt || { echo "FAIL no file:line:column in: $(cat err.txt)"; exit 1; }
echo PASS
