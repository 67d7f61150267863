"""cli.guided_reacquisition: PRN 25 blocked for 20 s, then received at 20 dB-Hz.

  python3 -m checks.guided_reacquisition WORK

WORK holds the ultra-tight runs guided and unguided (--no-guided-reacquisition).
"""
import math
import sys
from pathlib import Path

import products
from checklist import CheckList

PRN = 25
RISE_S = 20.0


def filter_satellites(run, from_s):
    return [int(r["filter_satellites"]) for r in products.pvt(run) if float(r["t_s"]) >= from_s and r["mode"] == "ultra"]


def main():
    work = Path(sys.argv[1])
    g, u = products.summary(work / "guided"), products.summary(work / "unguided")
    searches = [s for s in g["guided_searches"] if s["prn"] == PRN]
    print(f"PRN {PRN} searches:", ", ".join(f"{s['started_s']:.0f}-{s['ended_s']:.0f} s {s['outcome']}" for s in searches))
    checks = CheckList()
    # A search may end on another satellite's cross-correlation (named so, no channel started):
    # that is not PRN 25 found.
    early = [s for s in searches if s.get("detection") and s["ended_s"] < RISE_S and s["outcome"] != "cross-correlation"]
    checks.check(f"no signal of PRN {PRN} found while it was blocked", not early, early)
    confirmed = [s for s in searches if s["outcome"] == "confirmed"]
    if checks.check(f"PRN {PRN} found and confirmed", bool(confirmed)):
        c = confirmed[0]
        d = c["detection"]
        print(f"found {d['dwell_s']:.1f} s of integration, {d['cn0_dbhz']:.1f} dB-Hz, {d['code_offset_chips']:+.2f} chips, "
              f"{d['doppler_offset_hz']:+.1f} Hz from the prediction; confirmed at {c['ended_s']:.1f} s")
        checks.check("confirmed within 10 s of the rise", c["ended_s"] <= RISE_S + 10.0, f"{c['ended_s']:.1f} s")
        # The search's C/N0 is its dwell's mean: a dwell that began before the rise holds the
        # 20 dB-Hz signal only for its part after it.
        received = min(1.0, max(0.05, (c["started_s"] + d["dwell_s"] - RISE_S) / d["dwell_s"]))
        expected = 20.0 + 10.0 * math.log10(received)
        checks.check(f"search C/N0 within 3 dB of {expected:.1f} dB-Hz (20 dB-Hz for {received:.0%} of the dwell)",
                     abs(d["cn0_dbhz"] - expected) <= 3.0, f"{d['cn0_dbhz']:.1f} dB-Hz")
        checks.check("found within 0.25 chips of a prediction good to metres", abs(d["code_offset_chips"]) <= 0.25,
                     f"{d['code_offset_chips']:+.2f} chips")
    checks.check(f"--no-guided-reacquisition: PRN {PRN} neither acquired nor searched",
                 PRN not in u["acquired_prns"] and not u["guided_searches"], (u["acquired_prns"], u["guided_searches"]))
    after = filter_satellites(work / "guided", RISE_S + 10.0)
    checks.check(f"guided: 8 satellites in the filter after {RISE_S + 10:.0f} s", bool(after) and min(after) >= 8,
                 sorted(set(after)))
    checks.check("unguided: no more than the seven tracked satellites in the filter",
                 max(filter_satellites(work / "unguided", 0.0), default=0) <= 7)
    for name, s in (("guided", g), ("unguided", u)):
        checks.check(f"{name}: horizontal error <= 1.5 m", s["horizontal_error_m"]["max"] <= 1.5,
                     f"{s['horizontal_error_m']['max']:.2f} m")
    checks.exit()


if __name__ == "__main__":
    main()
