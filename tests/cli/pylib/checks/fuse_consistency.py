"""cli.fuse_consistency: `deepnav fuse` on the IF run's own RINEX products against that run.

  python3 -m checks.fuse_consistency offset IF_RUN_DIR    prints the receiver's time-tag
      offset from the IF file's sample time (seconds, to microseconds)
  python3 -m checks.fuse_consistency compare WORK OFFSET  checks the runs in WORK: if (the IF
      run), raw (fuse --no-smoothing) and smoothed (fuse), and the simulation sim
"""
import math
import statistics
import sys
from pathlib import Path

import products
from checklist import CheckList
from geodesy import difference_neu, rms


def time_offset_s(run):
    """The receiver's time tags are the sample time plus a constant (to microseconds)."""
    return statistics.median(float(r["gps_sow"]) - float(r["t_s"]) for r in products.pvt(run))


def tight_by_time(run):
    return {round(float(r["gps_sow"]), 3): r for r in products.pvt(run) if r["mode"] == "tight"}


def truth_rms_m(truth, rows, offset):
    # Epochs fall on whole seconds of sample time (to the microseconds of the time tags).
    at = {float(round(t - offset)): r for t, r in rows.items()}
    return rms(math.hypot(*difference_neu(r, truth[t])[:2]) for t, r in at.items() if t in truth)


def compare(work, offset):
    truth = products.truth_by_epoch(work / "sim")
    if_run, raw, smoothed = (tight_by_time(work / run) for run in ("if", "raw", "smoothed"))
    common = sorted(set(if_run) & set(raw))
    d = [difference_neu(if_run[t], raw[t]) for t in common]
    h = [math.hypot(n, e) for n, e, _ in d]
    d3 = [math.sqrt(n * n + e * e + u * u) for n, e, u in d]
    s = products.summary(work / "raw")
    jumps = len(s["observation_file"]["clock_jumps"])
    rejected = s["fusion"]["rows_rejected"]
    rms_if, rms_smoothed = truth_rms_m(truth, if_run, offset), truth_rms_m(truth, smoothed, offset)
    checks = CheckList()
    checks.check("at least 70 common tight epochs", len(common) >= 70, len(common))
    checks.check("fuse - IF horizontal difference <= 0.3 m", max(h, default=math.inf) <= 0.3,
                 f"max {max(h, default=math.inf):.3f} m, RMS {rms(h):.3f} m")
    checks.check("fuse - IF 3-D difference <= 0.5 m", max(d3, default=math.inf) <= 0.5,
                 f"max {max(d3, default=math.inf):.3f} m")
    checks.check("the receiver's clock re-sets found (it steps its time tags)", jumps >= 2, jumps)
    checks.check("at most 10 rows rejected", rejected <= 10, rejected)
    checks.check("smoothed fuse no further from the truth than the IF run (+5 cm)", rms_smoothed <= rms_if + 0.05,
                 f"fuse smoothed {rms_smoothed:.3f} m, IF {rms_if:.3f} m horizontal RMS")
    checks.exit()


def main():
    if sys.argv[1] == "offset":
        print(f"{time_offset_s(sys.argv[2]):.6f}")
    else:
        compare(Path(sys.argv[2]), float(sys.argv[3]))


if __name__ == "__main__":
    main()
