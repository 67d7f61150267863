"""cli.snap_static: the JSON of `deepnav snap` against the synthesizer's truth.

  python3 -m checks.snap fixes SNAP_JSON SIM_DIR --median-m M --max-m M [--time-correction-s S]
      every snapshot solved, its keys there, horizontal errors within the bounds, the time
      correction within 50 ms of S (the hint minus the true time, negated)
  python3 -m checks.snap refused SNAP_JSON WORD
      every snapshot unsolved: null coordinates and time, a reason naming WORD
"""
import argparse
import math

import products
from checklist import CheckList
from geodesy import ned_of_ecef_difference

KEYS = ["t_s", "lat_deg", "lon_deg", "height_m", "time_correction_s", "satellites", "used_prns", "residual_rms_m",
        "quality", "reason"]
SATELLITE_KEYS = ["prn", "code_phase_chips", "doppler_hz", "cn0_dbhz", "used", "residual_m"]


def llh_to_ecef(lat_deg, lon_deg, h_m):
    a, f = 6378137.0, 1 / 298.257223563
    e2 = f * (2 - f)
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = a / math.sqrt(1 - e2 * math.sin(lat) ** 2)
    return [(n + h_m) * math.cos(lat) * math.cos(lon), (n + h_m) * math.cos(lat) * math.sin(lon),
            (n * (1 - e2) + h_m) * math.sin(lat)]


def horizontal_error_m(snapshot, truth_row):
    fix = llh_to_ecef(snapshot["lat_deg"], snapshot["lon_deg"], snapshot["height_m"])
    true = [float(truth_row[axis + "_ecef_m"]) for axis in "xyz"]
    north, east, _ = ned_of_ecef_difference(snapshot["lat_deg"], snapshot["lon_deg"],
                                            [t - f for f, t in zip(fix, true)])
    return math.hypot(north, east)


def fixes(args, checks):
    snapshots = products.read_json(args.json)["snapshots"]
    truth = products.truth_by_epoch(args.sim)
    checks.check("snapshots taken", len(snapshots) >= args.count, len(snapshots))
    checks.check("every snapshot has the keys", all(all(k in s for k in KEYS) for s in snapshots),
                 [k for k in KEYS if k not in snapshots[0]])
    checks.check("every satellite entry has the keys",
                 all(all(k in sat for k in SATELLITE_KEYS) for s in snapshots for sat in s["satellites"]))
    solved = [s for s in snapshots if s["lat_deg"] is not None]
    checks.check("every snapshot solved", len(solved) == len(snapshots),
                 [s["reason"] for s in snapshots if s["lat_deg"] is None])
    errors = sorted(horizontal_error_m(s, truth[products.epoch_key(math.floor(s["t_s"] * 100) / 100)])
                    for s in solved)
    if errors:
        checks.check(f"median horizontal error <= {args.median_m} m", errors[len(errors) // 2] <= args.median_m,
                     round(errors[len(errors) // 2], 1))
        checks.check(f"largest horizontal error <= {args.max_m} m", errors[-1] <= args.max_m, round(errors[-1], 1))
    corrections = [s["time_correction_s"] for s in solved]
    checks.check(f"time corrections within 50 ms of {args.time_correction_s} s",
                 bool(corrections) and all(abs(c - args.time_correction_s) < 0.05 for c in corrections), corrections[:3])
    checks.check("the used satellites have residuals",
                 all(sat["residual_m"] is not None for s in solved for sat in s["satellites"] if sat["used"]))
    checks.check("quality flags of fixes", all(s["quality"] in ("good", "marginal") for s in solved))


def refused(args, checks):
    snapshots = products.read_json(args.json)["snapshots"]
    checks.check("snapshots taken", len(snapshots) >= 1, len(snapshots))
    for key in ("lat_deg", "lon_deg", "height_m", "time_correction_s"):
        checks.check(f"{key} null", all(s[key] is None for s in snapshots), [s[key] for s in snapshots])
    checks.check(f"a reason naming '{args.word}'", all(args.word in (s["reason"] or "") for s in snapshots),
                 snapshots[0]["reason"])
    checks.check("quality none", all(s["quality"] == "none" for s in snapshots))
    checks.check("the satellites found are listed", all(len(s["satellites"]) >= 6 for s in snapshots))


def main():
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="what", required=True)
    f = sub.add_parser("fixes")
    f.add_argument("json")
    f.add_argument("sim")
    f.add_argument("--median-m", type=float, required=True)
    f.add_argument("--max-m", type=float, required=True)
    f.add_argument("--count", type=int, default=1)
    f.add_argument("--time-correction-s", type=float, default=0.0)
    r = sub.add_parser("refused")
    r.add_argument("json")
    r.add_argument("word")
    args = parser.parse_args()
    checks = CheckList()
    (fixes if args.what == "fixes" else refused)(args, checks)
    checks.exit()


if __name__ == "__main__":
    main()
