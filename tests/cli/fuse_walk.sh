#!/usr/bin/env bash
# deepnav fuse on the real walk (data/walk_0827) from another working directory through
# its configuration file, scored against the RTK reference about its mean offset (the
# reference's base was not surveyed) and against RTKLIB's GPS L1 single point on the same
# epochs; the bounds are the figures results/fuse/README.md reports (0.623 m and 2.10 m
# tight, 0.666 m and 2.62 m loose) with a little to spare, and the issue's
# targets (tight scatter 0.7 m, no solution 5 m off, loose no worse than single point).
# Then bad inputs of each reader fail naming the file and the line.
#   usage: fuse_walk.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
for mode in tight loose; do
  "$deepnav" -q fuse --config "$src/data/walk_0827/walk.yaml" --mode $mode --out $mode \
    --compare "$src/results/fuse/rtklib_spp.pos" > $mode.txt || { echo "FAIL fuse $mode"; cat $mode.txt; exit 1; }
done
for f in pvt.csv fixes.nmea track.kml track.gpx obs.rnx nav.rnx summary.json filter.csv innovations.csv; do
  [ -s "tight/$f" ] || { echo "FAIL no tight/$f"; exit 1; }
done
python3 - "$work" <<'PY' || exit 1
import json, sys
bad = []
bounds = {"tight": (0.65, 2.3), "loose": (0.70, 2.8)}
for mode, (scatter_bound, max_bound) in bounds.items():
    s = json.load(open(f"{sys.argv[1]}/{mode}/summary.json"))
    ours = s["reference_errors"]["about_mean_offset"]
    spp = s["compare_errors"]["about_mean_offset"]
    print(f"{mode}: scatter {ours['rms_horizontal_m']} m, max 3-D {ours['max_3d_m']} m about the mean offset; "
          f"RTKLIB single point on the same epochs: scatter {spp['rms_horizontal_m']} m, max 3-D {spp['max_3d_m']} m")
    if ours["rms_horizontal_m"] > scatter_bound: bad.append(f"{mode} scatter {ours['rms_horizontal_m']} m > {scatter_bound} m")
    if ours["max_3d_m"] > max_bound: bad.append(f"{mode} max 3-D {ours['max_3d_m']} m > {max_bound} m")
    if ours["rms_horizontal_m"] > spp["rms_horizontal_m"]: bad.append(f"{mode} worse than single point")
    if s["reference_errors"]["epochs"] != 536: bad.append(f"{mode}: {s['reference_errors']['epochs']} epochs scored")
    if s["imu_log"]["duplicate_rows"] != 6958: bad.append(f"duplicate rows {s['imu_log']['duplicate_rows']}")
    if s["observation_file"]["skipped_satellite_records"].get("E", 0) == 0: bad.append("Galileo records not counted")
    if s["fusion"]["zero_velocity_updates"] == 0: bad.append(f"{mode}: no zero-velocity update (the walker stops)")
    if s["fusion"]["smoothing_doppler_steps"] == 0: bad.append(f"{mode}: no phase break carried by the Dopplers")
if bad:
    print("FAIL " + "; ".join(bad)); sys.exit(1)
PY
# Bad inputs, one per reader: a truncated observation file, an IMU log with a bad value, a
# navigation file with a bad number, a reference with a bad time.
head -c 20000 "$src/data/walk_0827/walk.obs" > cut.obs
printf '0,0,1,0,0,0,1000\n0,0,1,x,0,0,1010\n0,0,1,0,0,0,1020\n' > bad_imu.csv
sed '8s/^\(.\{30\}\)\(.\)/\1x/' "$src/data/walk_0827/walk.nav" > bad.nav
printf '%% reference\n2025/08/28 17:30:39.750 40.0967 -105.1471 1601.4 1 20\n2025/08/28 17:3O:40.000 40.0967 -105.1471 1601.4 1 20\n' > bad_ref.pos
expect_error() {  # expect_error PATTERN OPTIONS...: the run fails and stderr matches PATTERN
  local pattern=$1
  shift
  if "$deepnav" -q fuse --config "$src/data/walk_0827/walk.yaml" --out bad "$@" 2> err.txt > /dev/null; then
    echo "FAIL accepted: $*"; exit 1
  fi
  grep -q "$pattern" err.txt || { echo "FAIL '$pattern' not in: $(cat err.txt)"; exit 1; }
}
expect_error "cut.obs:[0-9]*:" --obs cut.obs
expect_error "bad_imu.csv:2: column 4 (gx)" --imu bad_imu.csv
expect_error "bad.nav:8:" --nav bad.nav
expect_error "bad_ref.pos:3: time '17:3O:40.000'" --reference bad_ref.pos
echo PASS
