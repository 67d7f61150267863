#!/usr/bin/env bash
# The recorded-data path against the IF path on one synthetic scenario (no real data): the
# land circle with a tactical IMU is synthesized, run through the IF receiver in tight
# mode, and its products (obs.rnx, nav.rnx) with the scenario's imu.csv are fed to
# `deepnav fuse --mode tight`. Without carrier smoothing (the IF run has none) the two
# solutions agree within a few decimetres on every epoch both have in tight mode; with it
# (fuse's default) fuse is no further from the truth than the IF run. The receiver steers
# its time tags by microsecond steps, which the RINEX reader must find as clock re-sets.
#   usage: fuse_consistency.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
sim_scenario "$src/data/scenarios/land_circle_aided_90s.yaml" "$work/sim"
sim_imu imu "$work/sim"
run_on_sim "$work/sim" "$work/if" --mode tight "${imu[@]}" "${assisted[@]}" --truth "$work/sim/truth.csv"
# The IMU's time is the IF file's sample time; the receiver's time tags are that plus a
# constant: the offset from the IF run's own pvt.csv.
offset=$(py -m checks.fuse_consistency offset "$work/if")
read -r grade lever_x lever_y lever_z <<< "$(py -m query imu "$work/sim/scenario.yaml")"
fuse() {  # fuse OUT [options]
  local out=$1
  shift
  "$deepnav" -q fuse --obs "$work/if/obs.rnx" --nav "$work/if/nav.rnx" --imu "$work/sim/imu.csv" --imu-format deepnav \
    --imu-time-base week-seconds --imu-time-offset "$offset" --imu-grade "$grade" --imu-grades-file "$imu_grades" \
    --imu-position "$lever_x" "$lever_y" "$lever_z" --mode tight --out "$work/$out" "$@" > "$work/$out.log" 2>&1 ||
    abort "fuse $*: $(tail -n 5 "$work/$out.log")"
}
fuse raw --no-smoothing
fuse smoothed
check_py "fuse agrees with the IF run" -m checks.fuse_consistency compare "$work" "$offset"
finish
