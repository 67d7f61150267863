#!/usr/bin/env python3
"""Horizontal error of `deepnav snap` against snapshot length.

Reads snapshot_outcomes.json, which `deepnav bench snapshot --plots-dir FOLDER` writes, and
writes snapshot_error.png there: the median and the 95th percentile of the horizontal error
per length, per scenario and over all, on logarithmic axes.
    usage: plot_snapshot.py FOLDER
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(folder):
    data = json.load(open(os.path.join(folder, "snapshot_outcomes.json")))
    rows = data["table"]["rows"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for scenario in dict.fromkeys(r["scenario"] for r in rows):
        mine = [r for r in rows if r["scenario"] == scenario and r["median_h_m"] is not None]
        lengths = [r["length_ms"] for r in mine]
        style = {"linewidth": 2.5, "color": "black"} if scenario == "all" else {"linewidth": 1.2}
        line, = ax.plot(lengths, [r["median_h_m"] for r in mine], marker="o", label=f"{scenario}: median", **style)
        ax.plot(lengths, [r["p95_h_m"] for r in mine], marker="^", linestyle="--", color=line.get_color(),
                linewidth=style["linewidth"], label=f"{scenario}: 95 %")
    ax.axhline(15, color="green", linewidth=0.8, linestyle=":", label="10 ms target: median 15 m")
    ax.axhline(40, color="red", linewidth=0.8, linestyle=":", label="10 ms target: 95 % 40 m")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("snapshot length (ms)")
    ax.set_ylabel("horizontal error (m)")
    notes = data["table"].get("notes", {})
    ax.set_title(f"deepnav snap at {notes.get('cn0_dbhz', '?')} dB-Hz, time hints off by up to "
                 f"{notes.get('max_time_error_s', '?')} s")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "snapshot_error.png"), dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
