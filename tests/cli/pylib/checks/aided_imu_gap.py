"""cli.aided_imu_gap: an ultra-tight run over an IMU log missing 12-16 s.

  python3 -m checks.aided_imu_gap SIM_DIR RUN_DIR

summary.json reports the one gap; no aided solution inside it; no published fix over 30 m
from the truth; ultra-tight again after it.
"""
import math
import sys

import products
from checklist import CheckList
from geodesy import ecef_m

GAP_S = (12.0, 16.0)


def main():
    sim, run = sys.argv[1:3]
    s = products.summary(run)
    truth = products.truth_by_epoch(sim)
    rows = products.pvt(run)
    checks = CheckList()
    gaps = s.get("imu_gaps", [])
    checks.check("summary.json: one IMU gap, 12-16 s", len(gaps) == 1 and abs(gaps[0]["from_s"] - GAP_S[0]) <= 0.02
                 and abs(gaps[0]["to_s"] - GAP_S[1]) <= 0.02, gaps)
    inside = [r for r in rows if GAP_S[0] + 0.1 <= float(r["t_s"]) < GAP_S[1]]
    aided_inside = [r["t_s"] for r in inside if r["mode"] in ("ultra", "tight", "loose", "coast")]
    checks.check(f"no aided solution inside the gap ({len(inside)} fixes from the receiver alone)", not aided_inside,
                 aided_inside[:5])
    errors = [math.dist(ecef_m(r), ecef_m(truth[products.epoch_key(r["t_s"])])) for r in rows
              if products.epoch_key(r["t_s"]) in truth]
    worst = max(errors, default=0.0)
    checks.check("no published fix over 30 m from the truth", worst <= 30.0, f"worst {worst:.1f} m")
    after = [r for r in rows if float(r["t_s"]) >= 20.0]
    back = [float(r["t_s"]) for r in rows if float(r["t_s"]) >= GAP_S[1] and r["mode"] == "ultra"]
    checks.check("ultra-tight again after the gap", any(r["mode"] == "ultra" for r in after),
                 f"from t = {min(back):.0f} s" if back else sorted({r["mode"] for r in after}))
    checks.exit()


if __name__ == "__main__":
    main()
