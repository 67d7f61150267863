"""cli.rtltcp_slow_sender: a run over rtltcp:// fed slower than real time.

  python3 -m checks.rtltcp_slow_sender RUN_DIR PACE

No gap and no lost sample (a slow sender is not a lossy one), the stream reported slower
than real time at PACE (within 10 %), each satellite in acquired_prns once (at least 4), and
no error.
"""
import sys

import products
from checklist import CheckList


def main():
    run, pace = sys.argv[1], float(sys.argv[2])
    s = products.summary(run)
    st = s["stream"]
    prns = s["acquired_prns"]
    checks = CheckList()
    checks.check("no gap", st["gaps"] == [], st["gaps"][:3])
    checks.check("no lost sample", st["lost_samples"] == 0, st["lost_samples"])
    checks.check("reported slower than real time", st["slower_than_real_time"] is True, st["slower_than_real_time"])
    checks.check(f"pace within 10 % of {pace}", abs(st["pace_of_real_time"] - pace) <= 0.1 * pace,
                 st["pace_of_real_time"])
    checks.check("each satellite listed once", len(prns) == len(set(prns)), prns)
    checks.check("at least 4 satellites", len(prns) >= 4, prns)
    checks.check("no error", s["error"] is None, s["error"])
    checks.exit()


if __name__ == "__main__":
    main()
