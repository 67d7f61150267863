"""cli.aided_outage: the land circle with every signal out from 60 to 90 s.

  python3 -m checks.aided_outage SIM_DIR WORK

WORK holds the runs ultra, tight and tight_withheld (tight with --max-solution-sigma 1.2).
For ultra and tight: the INS coasts through the gap within 5 m horizontally, sub-2 m after
it, every channel tracking again within 1 s, the solutions labelled coast (GGA quality 6)
in the outage and the mode's own after it. With the sigma limit: the end of the coast
withheld, every epoch after the return published.
"""
import json
import sys
from pathlib import Path

import products
from checklist import CheckList
from geodesy import horizontal_m

GAP_S = (60.0, 90.0)


def times_after_return(run):
    return [float(r["t_s"]) for r in products.pvt(run) if float(r["t_s"]) >= GAP_S[1] + 5]


def check_mode(checks, sim, run, mode):
    truth = products.truth_by_epoch(sim)
    rows = [r for r in products.pvt(run) if products.epoch_key(r["t_s"]) in truth]

    def error(r):
        return horizontal_m(r, truth[products.epoch_key(r["t_s"])])

    in_gap = [error(r) for r in rows if GAP_S[0] < float(r["t_s"]) <= GAP_S[1]]
    after = [error(r) for r in rows if float(r["t_s"]) >= GAP_S[1] + 3]
    checks.check(f"{mode}: a solution every second of the outage", len(in_gap) >= 29, len(in_gap))
    checks.check(f"{mode}: horizontal error <= 5 m during the outage", max(in_gap, default=float("inf")) <= 5.0,
                 f"{max(in_gap, default=float('inf')):.2f} m")
    checks.check(f"{mode}: horizontal error <= 2 m after the outage", max(after, default=float("inf")) <= 2.0,
                 f"{max(after, default=float('inf')):.2f} m")
    # Re-lock: the first integration of each satellite after the return tracking above 35 dB-Hz.
    relock = {}
    for r in products.tracking(run, products.sample_rate_hz(sim)):
        if r["t_s"] >= GAP_S[1] and r["prn"] not in relock and r["cn0_dbhz"] > 35.0 and r["state"] == "tracking":
            relock[r["prn"]] = r["t_s"] - GAP_S[1]
    late = {p: relock.get(p) for p in products.synthesized_prns(sim) if relock.get(p) is None or relock[p] > 1.0}
    checks.check(f"{mode}: every satellite tracked again within 1 s", not late,
                 f"late {late}" if late else f"{max(relock.values(), default=float('nan')):.2f} s")
    # Honest labels: through the outage the solution is the INS's (coast; NMEA GGA quality
    # 6), and it is the requested mode's again once the satellites are measured.
    labels_gap = {r["mode"] for r in rows if GAP_S[0] + 1 < float(r["t_s"]) <= GAP_S[1]}
    labels_after = {r["mode"] for r in rows if float(r["t_s"]) >= GAP_S[1] + 5}
    checks.check(f"{mode}: solutions in the outage labelled coast", labels_gap == {"coast"}, sorted(labels_gap))
    checks.check(f"{mode}: solutions after the outage labelled {mode}", labels_after == {mode}, sorted(labels_after))
    quality = [line.split(",")[6] for line in open(Path(run) / "fixes.nmea") if line.startswith("$GPGGA")]
    checks.check(f"{mode}: GGA quality 6 (dead reckoning) >= 28 times, 1 >= 30 times",
                 quality.count("6") >= 28 and quality.count("1") >= 30, (quality.count("6"), quality.count("1")))
    s = products.summary(run)
    print(f"{mode}: mode changes " + ", ".join(f"{c['t_s']:.0f} s {c['from']}->{c['to']}" for c in s["mode_changes"]))


def main():
    sim, work = sys.argv[1], Path(sys.argv[2])
    checks = CheckList()
    for mode in ("ultra", "tight"):
        check_mode(checks, sim, work / mode, mode)
    # The covariance limit: the late coast withheld, everything after the return published.
    withheld = products.summary(work / "tight_withheld")["withheld_solutions"]
    checks.check("--max-solution-sigma 1.2: the end of the 30 s coast withheld", 0 < withheld < 30,
                 f"{withheld} solutions withheld")
    checks.check("--max-solution-sigma 1.2: every epoch after the return published",
                 times_after_return(work / "tight_withheld") == times_after_return(work / "tight"))
    checks.exit()


if __name__ == "__main__":
    main()
