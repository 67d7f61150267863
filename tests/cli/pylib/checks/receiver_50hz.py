"""cli.receiver_50hz: fixes and RINEX epochs every 20 ms, metre-level errors, the
navigation-data report.

  python3 -m checks.receiver_50hz RUN_DIR
"""
import sys
from pathlib import Path

import products
from checklist import CheckList

RATE_HZ = 50


def main():
    run = Path(sys.argv[1])
    checks = CheckList()
    t = [float(r["t_s"]) for r in products.pvt(run)]
    steps = {round(b - a, 4) for a, b in zip(t, t[1:])}
    checks.check(f"at least 5 s of fixes at {RATE_HZ} Hz", len(t) >= RATE_HZ * 5, len(t))
    checks.check("fixes every 20 ms", steps == {1 / RATE_HZ}, sorted(steps)[:5])
    obs = (run / "obs.rnx").read_text()
    checks.check("RINEX INTERVAL 0.020", "     0.020 " in obs.split("END OF HEADER")[0])
    epochs = obs.count("\n> ")
    checks.check(f"at least 5 s of RINEX epochs at {RATE_HZ} Hz", epochs >= RATE_HZ * 5, epochs)
    s = products.summary(run)
    h = s["horizontal_error_m"]
    checks.check("horizontal RMS <= 3 m", h is not None and h["rms"] <= 3.0, h)
    nav = s.get("navigation", [])
    checks.check("navigation report: 4 or more satellites, each tracked",
                 len(nav) >= 4 and all(n["parity_failures"] >= 0 and n["tracked_s"] > 0 for n in nav), nav)
    checks.exit()


if __name__ == "__main__":
    main()
