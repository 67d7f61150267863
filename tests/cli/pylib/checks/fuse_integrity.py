"""cli.fuse_integrity: what `deepnav fuse` publishes where its inputs fall short.

  python3 -m checks.fuse_integrity imu-gap RUN FROM_S TO_S
      the INS stopped once, at the gap: no epoch inside it is labelled with a coupling mode
      (only the single point, "scalar"), the filter runs again after it, and no published
      solution is over 10 m from the reference (about its mean offset)
  python3 -m checks.fuse_integrity imu-end RUN END_S
      the log's end reported at END_S; every epoch after it is the single point
  python3 -m checks.fuse_integrity no-score RUN
      no epoch scored against the reference: every statistic null, none a 0.0

RUN is a fuse output folder; times are seconds since the first epoch (pvt.csv's t_s).
"""
import sys

import products
from checklist import CheckList

COUPLED = ("loose", "tight", "coast")
MAX_ERROR_M = 10.0


def modes_between(rows, t_from, t_to):
    return sorted({r["mode"] for r in rows if t_from < float(r["t_s"]) < t_to})


def within_reference(checks, s):
    worst = s["reference_errors"]["about_mean_offset"]["max_3d_m"]
    checks.check(f"every solution within {MAX_ERROR_M} m of the reference (about its offset)",
                 worst is not None and worst <= MAX_ERROR_M, worst)


def imu_gap(run, t_from, t_to):
    checks = CheckList("imu gap")
    s, rows = products.summary(run), products.pvt(run)
    checks.check("the INS stopped once", s["fusion"]["imu_gap_stops"] == 1, s["fusion"]["imu_gap_stops"])
    checks.check("summary.json lists the gap", len(s["imu_log"]["gaps"]) == 1, s["imu_log"]["gaps"])
    inside = modes_between(rows, t_from + 0.1, t_to)
    checks.check("inside the gap only the single point", inside == ["scalar"], inside)
    after = modes_between(rows, t_to, 1e9)
    checks.check("the filter again after the gap", any(m in COUPLED for m in after), after)
    within_reference(checks, s)
    return checks


def imu_end(run, t_end):
    checks = CheckList("imu end")
    s, rows = products.summary(run), products.pvt(run)
    end = s["fusion"]["imu_end_s"]
    checks.check(f"the log's end reported at {t_end} s", end is not None and abs(end - t_end) < 0.05, end)
    after = modes_between(rows, t_end + 0.1, 1e9)
    checks.check("after it only the single point", after == ["scalar"], after)
    within_reference(checks, s)
    return checks


def no_score(run):
    checks = CheckList("no epoch scored")
    e = products.summary(run)["reference_errors"]
    checks.check("0 epochs", e["epochs"] == 0, e["epochs"])
    statistics = [e["mean_offset_enu_m"], e["rms_horizontal_m"], e["rms_vertical_m"], e["rms_3d_m"],
                  *e["about_mean_offset"].values()]
    checks.check("every statistic null", all(v is None for v in statistics), statistics)
    return checks


def main():
    what, run, *times = sys.argv[1:]
    if what == "imu-gap":
        checks = imu_gap(run, float(times[0]), float(times[1]))
    elif what == "imu-end":
        checks = imu_end(run, float(times[0]))
    elif what == "no-score":
        checks = no_score(run)
    else:
        sys.exit(__doc__)
    checks.exit()


if __name__ == "__main__":
    main()
