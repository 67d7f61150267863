"""cli.receiver_land_circle: every synthesized satellite tracked from start to end.

  python3 -m checks.receiver_land_circle SIM_DIR RUN_DIR
"""
import sys

import products
from checklist import CheckList


def main():
    sim, run = sys.argv[1:3]
    duration_s = products.synthesis(sim)["duration_s"]
    first, last, state = {}, {}, {}
    for r in products.tracking(run, products.sample_rate_hz(sim)):
        first.setdefault(r["prn"], r["t_s"])
        last[r["prn"]] = r["t_s"]
        state[r["prn"]] = r["state"]
    checks = CheckList()
    for prn in products.synthesized_prns(sim):
        if checks.check(f"PRN {prn} tracked", prn in first):
            checks.check(f"PRN {prn} tracked from the start to the end, tracking at the end",
                         first[prn] <= 0.1 and last[prn] >= duration_s - 0.1 and state[prn] == "tracking",
                         f"{first[prn]:.2f}-{last[prn]:.2f} s, final state {state[prn]}")
    h = products.summary(run)["horizontal_error_m"]
    checks.check("horizontal RMS <= 3 m", h is not None and h["rms"] <= 3.0, h)
    checks.exit()


if __name__ == "__main__":
    main()
