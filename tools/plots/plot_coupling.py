#!/usr/bin/python3
"""Horizontal position error over time for the circle trajectories, one line per mode
(first Monte Carlo run), from the CSV that `deepnav bench coupling --csv` writes.
usage: plot_coupling.py errors.csv out.png"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    src, out = sys.argv[1], sys.argv[2]
    series = {}
    for r in csv.DictReader(open(src)):
        if r["run"] != "0" or r["valid"] != "1" or "circle" not in r["trajectory"]:
            continue
        key = (r["trajectory"], r["requested_mode"])
        series.setdefault(key, ([], []))
        series[key][0].append(float(r["t_s"]))
        series[key][1].append(math.hypot(float(r["error_n_m"]), float(r["error_e_m"])))
    trajectories = sorted({k[0] for k in series})
    if not trajectories:
        sys.exit("no circle trajectory in " + src)
    fig, axes = plt.subplots(len(trajectories), 1, figsize=(9, 3.2 * len(trajectories)), squeeze=False)
    for ax, traj in zip(axes[:, 0], trajectories):
        for (t, mode), (ts, es) in sorted(series.items()):
            if t == traj:
                ax.plot(ts, es, label=mode, lw=1)
        ax.set_title(traj)
        ax.set_ylabel("horizontal error (m)")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    axes[-1, 0].set_xlabel("time (s)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
