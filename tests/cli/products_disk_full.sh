#!/usr/bin/env bash
# A full disk must cost neither the products that fit nor the summary that says what
# happened. tracking.csv, the product that fills it, is left out (its partial file removed
# at once, so its space goes back to the others), and so is an earlier run's tracking.csv,
# which this run can no longer replace; every other product and summary.json are complete
# and this run's, summary.json names the failed product and why, and the run exits 1 saying
# so. First on a small tmpfs when one can be mounted here (as root, or in a user namespace),
# then always on the output layer's simulated disk (DEEPNAV_TEST_DISK_BYTES). fuse the same;
# acquire --json /dev/full, or on a full disk, is an error, not exit 0 and an empty file.
#   usage: products_disk_full.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
# 16 s from 3 s before a subframe: an assisted start fixes from about 11 s. tracking.csv
# grows by about 100 kB/s; the other products stay under 20 kB, summary.json reserves 256 kB.
derive_scenario "$src/data/scenarios/default.yaml" "$work/short.yaml" 'start_time: "2022-01-01T01:59:57"' \
  'duration_s: 16' 'sample_rate_hz: 2046000' "nav_file: $brdc"
sim_scenario "$work/short.yaml" "$work/sim"
sim_source source "$work/sim"
run=("$deepnav" -q run "${source[@]}" "${assisted[@]}" --threads 1)
disk_bytes=700000
products=(pvt.csv nav.rnx obs.rnx fixes.nmea track.kml track.gpx summary.json)

# check_lost_tracking NAME OUT: OUT holds every product but tracking.csv, summary.json says
# why tracking.csv is missing, and pvt.csv has this run's fixes.
check_lost_tracking() {
  local name=$1 out=$2 f fixes rows
  for f in "${products[@]}"; do check "$name: $f written" '[[ -s $out/$f ]]'; done
  check "$name: no tracking.csv" '[[ ! -e $out/tracking.csv ]]'
  check "$name: no partial file" '! ls "$out" | grep -q partial'
  check_json_each "$out/summary.json" \
    "$name: one product failed" 'len(products_failed)' '==' 1 \
    "$name: it is tracking.csv" products_failed.0.product '==' '"tracking.csv"' \
    "$name: for want of space" products_failed.0.error contains '"No space left on device"' \
    "$name: fixes" fixes '>' 0
  fixes=$(json_value "$out/summary.json" fixes)
  rows=$(($(wc -l < "$out/pvt.csv") - 1))
  check "$name: pvt.csv has the summary's $fixes fixes ($rows rows)" '[[ $rows -eq $fixes ]]'
}

lost_message=("1 of the products could not be written (the others are): tracking.csv: cannot write" \
  "tracking.csv': No space left on device")

# A real full disk: a tmpfs of the size above.
mkdir "$work/mount"
if "$src/tests/cli/lib/in_tmpfs.sh" --probe "$work/mount"; then
  "$src/tests/cli/lib/in_tmpfs.sh" "$disk_bytes" "$work/mount" "$work/tmpfs" -- "${run[@]}" --out "$work/mount/run"
  status=$(cat "$work/tmpfs.status")
  check "tmpfs: exit 1 ($status)" '[[ $status -eq 1 ]]'
  for fragment in "${lost_message[@]}"; do check "tmpfs: the message says '$fragment'" 'grep -qF "$fragment" "$work/tmpfs.log"'; done
  check_lost_tracking tmpfs "$work/tmpfs/run"
else
  echo "skip tmpfs (no tmpfs can be mounted here): the simulated disk below stands for it"
fi

# The simulated disk, over an earlier complete run at 2 Hz: what this run could not replace
# is removed, the rest is this run's.
run_receiver "$work/run" "${source[@]}" "${assisted[@]}" --threads 1 --rate 2
check "the earlier run wrote tracking.csv" '[[ -s $work/run/tracking.csv ]]'
DEEPNAV_TEST_DISK_BYTES=$disk_bytes EXIT_STATUS=1 expect_failure "simulated disk: exit 1" \
  "${lost_message[@]}" "(an earlier run's file of that name is removed)" -- "${run[@]}" --out "$work/run"
check "a warning when tracking.csv failed" 'grep -q "tracking.csv: .* this product is left out, the others go on" <<< "$failure_output"'
check_lost_tracking "simulated disk" "$work/run"
check_json "this run's summary (1 Hz: 16 epochs)" "$work/run/summary.json" epochs '==' 16

# summary.json's own space is reserved: a disk without room even for that warns, then
# every product fails, the summary too, each named, and nothing is left.
DEEPNAV_TEST_DISK_BYTES=0 EXIT_STATUS=1 expect_failure "a disk without room for anything" \
  "cannot reserve 262144 bytes for '$work/nothing/summary.json': No space left on device" \
  "7 of the products could not be written" \
  "summary.json: cannot write '$work/nothing/summary.json': No space left on device" -- \
  "${run[@]}" --out "$work/nothing"
check "no file left" '[[ -z $(ls "$work/nothing") ]]'

# fuse on the walk (800 kB of products): each product is there or named as failed.
walk=$src/data/walk_0827
DEEPNAV_TEST_DISK_BYTES=650000 EXIT_STATUS=1 expect_failure "fuse on a full disk" \
  "of the products could not be written (the others are)" "No space left on device" -- \
  "$deepnav" -q fuse --config "$walk/walk.yaml" --out "$work/fuse"
check_json_each "$work/fuse/summary.json" \
  "fuse: a product failed" 'len(products_failed)' '>=' 1 \
  "fuse: for want of space" products_failed.0.error contains '"No space left on device"' \
  "fuse: every epoch" epochs '==' 536
failed=$(json_value "$work/fuse/summary.json" products_failed)
for f in pvt.csv fixes.nmea obs.rnx nav.rnx filter.csv innovations.csv; do
  if [[ $failed == *"\"$f\""* ]]; then
    check "fuse: $f failed, absent" '[[ ! -e $work/fuse/$f ]]'
  else
    check "fuse: $f written" '[[ -s $work/fuse/$f ]]'
  fi
done
check "fuse: no partial file" '! ls "$work/fuse" | grep -q partial'

# acquire --json on a full device: an error naming it.
EXIT_STATUS=1 expect_failure "acquire --json /dev/full" "cannot write '/dev/full': No space left on device" -- \
  "$deepnav" -q acquire "${source[@]:0:6}" --json /dev/full
# ... and on a full disk: no empty acq.json, nor an earlier one passing for this result.
echo '{"earlier": true}' > "$work/acq.json"
DEEPNAV_TEST_DISK_BYTES=100 EXIT_STATUS=1 expect_failure "acquire --json on a full disk" \
  "cannot write '$work/acq.json': No space left on device (an earlier run's file of that name is removed)" -- \
  "$deepnav" -q acquire "${source[@]:0:6}" --json "$work/acq.json"
check "acquire: no acq.json left" '[[ -z $(compgen -G "$work/acq.json*") ]]'
finish
