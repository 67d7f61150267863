"""Plots for `deepnav bench leverarm` (paper 004 [docs/references.md] Figs. 2-4 and 6 style).
Usage: plot_leverarm.py DIR (reads DIR/leverarm_traces.json)."""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    out_dir = sys.argv[1]
    with open(os.path.join(out_dir, "leverarm_traces.json")) as f:
        data = json.load(f)
    t = data["ship_t_s"]

    fig, axes = plt.subplots(3, 1, figsize=(9, 10), sharex=True)
    axes[0].plot(t, data["ship_roll_deg"], "k")
    axes[0].set_ylabel("roll [deg]")
    axes[0].set_title("Ship roll (moment applied 5-15 s)")
    for run in data["ship"]:
        label = f"{run['arm_m']:.2f} m"
        axes[1].plot(t, run["conventional_err_deg"], label=label, linewidth=0.9)
        axes[2].plot(t, run["proposed_err_deg"], label=label, linewidth=0.9)
    axes[1].set_title("Roll error, conventional filter (no lever-arm state)")
    axes[2].set_title("Roll error, filter with lever-arm state")
    for ax in axes[1:]:
        ax.axvspan(10, 12, color="0.9", zorder=0)
        ax.set_ylabel("roll error [deg]")
        ax.legend(fontsize=8, ncol=4)
    lim = max(abs(v) for run in data["ship"] for v in run["conventional_err_deg"]) * 1.1
    for ax in axes[1:]:
        ax.set_ylim(-lim, lim)
        ax.grid(True, alpha=0.3)
    axes[0].grid(True, alpha=0.3)
    axes[2].set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "leverarm_roll_error.png"), dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(9, 4))
    for run in data["ship"]:
        line, = ax.plot(t, run["est_arm_m"], label=f"true {run['arm_m']:.2f} m")
        ax.axhline(run["arm_m"], color=line.get_color(), linestyle=":", linewidth=0.8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("estimated arm above CG [m]")
    ax.set_title("Lever-arm state of the 8-state filter")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "leverarm_estimate.png"), dpi=120)
    plt.close(fig)

    rt = data.get("rate_table")
    if rt:
        fig, ax = plt.subplots(figsize=(9, 4))
        ax.plot(rt["t_s"], rt["conventional_err_deg"], "-", label="without lever-arm state")
        ax.plot(rt["t_s"], rt["proposed_err_deg"], ":", label="with lever-arm state")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("roll error [deg]")
        ax.set_title("Rate table: 18 cm arm, 30 deg / 2 s roll sine")
        ax.legend()
        ax.grid(True, alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, "leverarm_rate_table.png"), dpi=120)
        plt.close(fig)


if __name__ == "__main__":
    main()
