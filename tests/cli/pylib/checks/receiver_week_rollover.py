"""cli.receiver_week_rollover: a run across a GPS week boundary dated by the truth.

  python3 -m checks.receiver_week_rollover RUN_DIR SIM_DIR [--both-weeks]

Every fix of pvt.csv (week and second of week) lies within 10 ms of the truth's GPS time at
its t_s (a last fix after the truth's last epoch aside), and every obs.rnx epoch within the
truth's span; with --both-weeks there are fixes
on both sides of the boundary. summary.json holds no error.
"""
import argparse
import datetime
from pathlib import Path

import products
from checklist import CheckList

SECONDS_PER_WEEK = 604800
GPS_EPOCH = datetime.datetime(1980, 1, 6)


def gps_seconds(week, sow):
    return int(week) * SECONDS_PER_WEEK + float(sow)


def obs_epochs(run):
    """GPS seconds of each obs.rnx epoch line ('> 2022 01 02 00 00  7.0000000  0 ...')."""
    out = []
    for line in (Path(run) / "obs.rnx").read_text().splitlines():
        if line.startswith(">"):
            y, mo, d, h, mi, s = line[1:].split()[:6]
            whole = datetime.datetime(int(y), int(mo), int(d), int(h), int(mi))
            out.append((whole - GPS_EPOCH).total_seconds() + float(s))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run")
    ap.add_argument("sim")
    ap.add_argument("--both-weeks", action="store_true")
    a = ap.parse_args()
    checks = CheckList()
    checks.check("summary.json: no error", products.summary(a.run)["error"] is None, products.summary(a.run)["error"])
    truth = {products.epoch_key(r["t_s"]): gps_seconds(r["gps_week"], r["gps_sow"])
             for r in products.read_csv(Path(a.sim) / "truth.csv")}
    rows = products.pvt(a.run)
    # The truth ends at the scenario's last epoch before its duration: a fix at the very end
    # has none to compare with.
    last_truth_t = max(truth)
    beyond = [r for r in rows if products.epoch_key(r["t_s"]) > last_truth_t]
    checks.check("pvt.csv: every fix but one at the very end has a truth epoch",
                 len(beyond) <= 1 and all(products.epoch_key(r["t_s"]) not in truth for r in beyond),
                 [r["t_s"] for r in beyond])
    off = [gps_seconds(r["gps_week"], r["gps_sow"]) - truth[products.epoch_key(r["t_s"])] for r in rows
           if products.epoch_key(r["t_s"]) in truth]
    worst = max((abs(x) for x in off), default=0.0)
    checks.check("pvt.csv: every fix within 10 ms of the truth's GPS time", worst < 0.010,
                 f"{len(off)} fixes, worst {worst:.6f} s")
    if a.both_weeks:
        weeks = sorted({r["gps_week"] for r in rows})
        checks.check("pvt.csv: fixes in both weeks", len(weeks) == 2, weeks)
    first, last = min(truth.values()), max(truth.values())
    epochs = obs_epochs(a.run)
    outside = [e for e in epochs if not first - 1.0 <= e <= last + 1.0]
    checks.check("obs.rnx: every epoch within the truth's span", bool(epochs) and not outside,
                 f"{len(epochs)} epochs, {len(outside)} outside, e.g. {outside[:1]}")
    checks.exit()


if __name__ == "__main__":
    main()
