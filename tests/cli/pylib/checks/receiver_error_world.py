"""cli.receiver_error_world: the `none` and `suburban` error worlds through the receiver.

  python3 -m checks.receiver_error_world WORK

WORK holds sim_none, sim_suburban (simulations) and run_none, run_suburban (their runs).
"""
import sys
from pathlib import Path

import products
from checklist import CheckList
from geodesy import rms


def error_budget(sim):
    """RMS over the transmitting satellites of each error sat_truth.csv carries, metres."""
    rows = [r for r in products.read_csv(Path(sim) / "sat_truth.csv") if r["transmitting"] == "1"]
    return {"iono_residual": rms(float(r["iono_m"]) - float(r["iono_broadcast_m"]) for r in rows),
            "orbit": rms(float(r["orbit_m"]) for r in rows),
            "clock": rms(float(r["sat_clock_error_m"]) for r in rows),
            "multipath": rms(float(r["multipath_m"]) for r in rows)}


def main():
    work = Path(sys.argv[1])
    worlds = ("none", "suburban")
    summaries = {w: products.summary(work / f"run_{w}") for w in worlds}
    none, sub = (error_budget(work / f"sim_{w}") for w in worlds)
    h = {w: summaries[w]["horizontal_error_m"]["rms"] for w in worlds}
    v = {w: summaries[w]["vertical_error_m"]["rms"] for w in worlds}
    error_3d = {w: (h[w] ** 2 + v[w] ** 2) ** 0.5 for w in worlds}
    checks = CheckList()
    checks.check("none: every error column zero", all(x == 0.0 for x in none.values()), none)
    checks.check("suburban: ionosphere residual RMS >= 0.3 m", sub["iono_residual"] >= 0.3, sub["iono_residual"])
    checks.check("suburban: orbit and clock errors present", sub["orbit"] > 0.05 and sub["clock"] > 0.05,
                 (sub["orbit"], sub["clock"]))
    checks.check("suburban: multipath present", sub["multipath"] > 0.1, sub["multipath"])
    checks.check("suburban 3-D RMS error > none's + 0.5 m", error_3d["suburban"] > error_3d["none"] + 0.5, (h, v))
    checks.exit()


if __name__ == "__main__":
    main()
