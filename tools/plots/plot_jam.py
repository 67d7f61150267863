#!/usr/bin/env python3
"""Plots of `deepnav bench jam`: for each jammer in DIR/runs.csv, one PNG (DIR/jam_<jammer>.png)
with the horizontal position error (RMS and max, every solution), the GNSS fix availability
(and, dashed, that of any solution, an aided mode's INS coast included), the post-correlation
C/N0, and the tracked and signal fractions against J/S, one line per receiver mode and mitigation (seeds
averaged).
usage: plot_jam.py DIR"""
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    return float(text) if text not in ("", None) else math.nan


def mean(values):
    values = [v for v in values if not math.isnan(v)]
    return sum(values) / len(values) if values else math.nan


def main(folder):
    rows = list(csv.DictReader(open(os.path.join(folder, "runs.csv"))))
    by_jammer = defaultdict(lambda: defaultdict(lambda: defaultdict(list)))
    for r in rows:
        key = f"{r['mode']} / {r['mitigation']}"
        by_jammer[(r["scenario"], r["jammer"])][key][number(r["js_db"])].append(r)
    for (scenario, jammer), series in sorted(by_jammer.items()):
        fig, axes = plt.subplots(4, 1, figsize=(7.5, 12), sharex=True)
        for i, (label, points) in enumerate(sorted(series.items())):
            js = sorted(points)
            color = f"C{i}"
            h_rms = [mean([number(r["horizontal_rms_m"]) for r in points[x]]) for x in js]
            h_max = [mean([number(r["horizontal_max_m"]) for r in points[x]]) for x in js]
            cn0 = [mean([number(r["cn0_mean_dbhz"]) for r in points[x]]) for x in js]
            tracked = [mean([number(r["tracked_fraction_mean"]) for r in points[x]]) for x in js]
            signal = [mean([number(r.get("signal_fraction_mean", "")) for r in points[x]]) for x in js]
            fixes = [mean([number(r["fix_availability"]) for r in points[x]]) for x in js]
            solutions = [mean([number(r.get("solution_availability", "")) for r in points[x]]) for x in js]
            axes[0].semilogy(js, h_rms, "o-", color=color, label=f"{label} RMS")
            axes[0].semilogy(js, h_max, "x--", color=color, label=f"{label} max")
            axes[1].plot(js, fixes, "o-", color=color, label=f"{label} GNSS fixes")
            axes[1].plot(js, solutions, "x--", color=color, label=f"{label} any solution")
            axes[2].plot(js, cn0, "o-", color=color, label=label)
            axes[3].plot(js, tracked, "o-", color=color, label=f"{label} tracked")
            axes[3].plot(js, signal, "x--", color=color, label=f"{label} signal (15 dB-Hz)")
        axes[0].axhline(10.0, color="k", lw=0.8, ls=":")
        axes[0].set_ylabel("horizontal error (m)")
        axes[0].legend(fontsize=7)
        axes[1].axhline(0.95, color="k", lw=0.8, ls=":")
        axes[1].set_ylabel("availability")
        axes[1].set_ylim(-0.05, 1.05)
        axes[1].legend(fontsize=7)
        axes[2].set_ylabel("post-correlation C/N0 (dB-Hz)")
        axes[2].legend(fontsize=7)
        axes[3].set_ylabel("fraction of the jammed time (mean)")
        axes[3].legend(fontsize=7)
        axes[3].set_ylim(-0.05, 1.05)
        axes[3].set_xlabel("J/S (dB)")
        for ax in axes:
            ax.grid(True, which="both", alpha=0.3)
        axes[0].set_title(f"{scenario}: {jammer} jammer (missing points: no fix / no tracking)")
        fig.tight_layout()
        fig.savefig(os.path.join(folder, f"jam_{jammer}.png"), dpi=110)
        plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
