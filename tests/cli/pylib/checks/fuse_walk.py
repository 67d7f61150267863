"""cli.fuse_walk: `deepnav fuse` on the real walk, tight and loose.

  python3 -m checks.fuse_walk WORK

Each mode's scatter and worst 3-D error about the RTK reference's mean offset within the
figures results/fuse/README.md reports (with a little to spare), no worse than RTKLIB's
single point, and the readers' and the filter's counts as the walk's data give them.
"""
import sys
from pathlib import Path

import products
from checklist import CheckList

# mode: (horizontal scatter bound, worst 3-D bound) about the mean offset, metres.
BOUNDS_M = {"tight": (0.62, 2.2), "loose": (0.68, 2.8)}


def main():
    work = Path(sys.argv[1])
    checks = CheckList()
    for mode, (scatter_bound, max_bound) in BOUNDS_M.items():
        s = products.summary(work / mode)
        ours = s["reference_errors"]["about_mean_offset"]
        spp = s["compare_errors"]["about_mean_offset"]
        print(f"{mode}: RTKLIB single point on the same epochs: scatter {spp['rms_horizontal_m']} m, "
              f"max 3-D {spp['max_3d_m']} m")
        checks.check(f"{mode}: scatter <= {scatter_bound} m", ours["rms_horizontal_m"] <= scatter_bound,
                     ours["rms_horizontal_m"])
        checks.check(f"{mode}: max 3-D <= {max_bound} m", ours["max_3d_m"] <= max_bound, ours["max_3d_m"])
        checks.check(f"{mode}: no worse than single point", ours["rms_horizontal_m"] <= spp["rms_horizontal_m"],
                     (ours["rms_horizontal_m"], spp["rms_horizontal_m"]))
        checks.check(f"{mode}: 536 epochs scored", s["reference_errors"]["epochs"] == 536, s["reference_errors"]["epochs"])
        # The logger reads its 100 Hz IMU every 6 to 9 ms: 6958 rows repeat the row before at a
        # new time, and are samples all the same (the rate held over their interval).
        imu = s["imu_log"]
        checks.check(f"{mode}: 6958 repeated IMU values kept, no row dropped",
                     (imu["repeated_values"], imu["duplicate_rows"], imu["samples"]) == (6958, 0, imu["rows"]),
                     (imu["repeated_values"], imu["duplicate_rows"], imu["samples"], imu["rows"]))
        skipped = s["observation_file"]["skipped_satellite_records"]
        checks.check(f"{mode}: Galileo records counted", skipped.get("E", 0) > 0, skipped)
        checks.check(f"{mode}: zero-velocity updates (the walker stops)", s["fusion"]["zero_velocity_updates"] > 0,
                     s["fusion"]["zero_velocity_updates"])
        checks.check(f"{mode}: phase breaks carried by the Dopplers", s["fusion"]["smoothing_doppler_steps"] > 0,
                     s["fusion"]["smoothing_doppler_steps"])
    checks.exit()


if __name__ == "__main__":
    main()
