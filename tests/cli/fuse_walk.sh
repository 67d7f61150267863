#!/usr/bin/env bash
# deepnav fuse on the real walk (data/walk_0827) from another working directory through
# its configuration file, scored against the RTK reference about its mean offset (the
# reference's base was not surveyed) and against RTKLIB's GPS L1 single point on the same
# epochs; the bounds are the figures results/fuse/README.md reports (0.579 m and 2.06 m
# tight, 0.637 m and 2.61 m loose) with a little to spare, and the issue's
# targets (tight scatter 0.7 m, no solution 5 m off, loose no worse than single point).
# Then bad inputs of each reader fail naming the file and the line.
#   usage: fuse_walk.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
walk=$src/data/walk_0827
cd "$work"
for mode in tight loose; do
  "$deepnav" -q fuse --config "$walk/walk.yaml" --mode $mode --out $mode --compare "$src/results/fuse/rtklib_spp.pos" \
    > $mode.txt 2>&1 || abort "fuse $mode: $(cat $mode.txt)"
done
for f in pvt.csv fixes.nmea track.kml track.gpx obs.rnx nav.rnx summary.json filter.csv innovations.csv; do
  check "tight/$f written" '[[ -s tight/$f ]]'
done
check_py "the walk against the reference and single point" -m checks.fuse_walk "$work"
# Bad inputs, one per reader: a truncated observation file, an IMU log with a bad value, a
# navigation file with a bad number, a reference with a bad time.
head -c 20000 "$walk/walk.obs" > cut.obs
printf '0,0,1,0,0,0,1000\n0,0,1,x,0,0,1010\n0,0,1,0,0,0,1020\n' > bad_imu.csv
sed '8s/^\(.\{30\}\)\(.\)/\1x/' "$walk/walk.nav" > bad.nav
printf '%% reference\n2025/08/28 17:30:39.750 40.0967 -105.1471 1601.4 1 20\n2025/08/28 17:3O:40.000 40.0967 -105.1471 1601.4 1 20\n' \
  > bad_ref.pos
bad_fuse() { "$deepnav" -q fuse --config "$walk/walk.yaml" --out bad "$@" 2>&1 >/dev/null; }  # stderr alone
expect_failure "truncated observation file" --grep "cut.obs:[0-9]*:" -- bad_fuse --obs cut.obs
expect_failure "IMU log with a bad value" "bad_imu.csv:2: column 4 (gx)" -- bad_fuse --imu bad_imu.csv
expect_failure "navigation file with a bad number" "bad.nav:8:" -- bad_fuse --nav bad.nav
expect_failure "reference with a bad time" "bad_ref.pos:3: time '17:3O:40.000'" -- bad_fuse --reference bad_ref.pos
finish
