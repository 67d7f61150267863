"""Plots for `deepnav bench align`: paper 000 [docs/references.md] Figs. 2-4 style error sweeps, the
simulated-vs-analytic agreement, and fine-alignment heading convergence.
Usage: plot_align.py DIR (reads DIR/align_sweep.json and DIR/align_fine.json)."""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ANGLES = [("roll", 0, "fig2_roll"), ("pitch", 1, "fig3_pitch"), ("yaw", 2, "fig4_yaw")]
METHODS = ["one-shot", "two-step"]


def x_of(case):
    # Common abscissa: accelerometer ug, gyro deg/h x 100 (1-100 ug <-> 0.01-1 deg/h).
    return case["magnitude"] * (100.0 if case["sensor"] == "gyro" else 1.0)


def sweep_figures(sweep, out_dir):
    for name, k, stem in ANGLES:
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
        for ax, method in zip(axes, METHODS):
            cases = [c for c in sweep if c["method"] == method]
            srss = {}
            for sensor in ("accel", "gyro"):
                for axis in "xyz":
                    pts = sorted((x_of(c), abs(c["sim_euler_deg"][k]), abs(c["analytic_tilt_deg"][k]))
                                 for c in cases if c["sensor"] == sensor and c["axis"] == axis)
                    if not pts:
                        continue
                    xs = [p[0] for p in pts]
                    line, = ax.plot(xs, [max(p[1], 1e-9) for p in pts], label=f"{sensor} {axis}")
                    ax.plot(xs, [max(p[2], 1e-9) for p in pts], "--", color=line.get_color(), linewidth=0.8)
                    for x, sim, _ in pts:
                        key = round(x, 6)
                        srss[key] = srss.get(key, 0.0) + sim * sim
            xs = sorted(srss)
            ax.plot(xs, [math.sqrt(srss[x]) for x in xs], "k", linewidth=2, label="SRSS")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_ylim(1e-6, 10)
            ax.set_title(f"{method}: {name} error")
            ax.set_xlabel("sensor error: accel [ug], gyro [deg/h x 100]")
            ax.grid(True, which="both", alpha=0.3)
        axes[0].set_ylabel(f"|{name} error| [deg] (solid: simulated, dashed: analytic)")
        axes[1].legend(fontsize=8)
        fig.suptitle("Coarse alignment, latitude 35 deg, attitude (5, 5, 5) deg")
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, f"align_{stem}.png"), dpi=120)
        plt.close(fig)


def agreement_figure(sweep, out_dir):
    fig, ax = plt.subplots(figsize=(5.5, 5))
    for method, marker in zip(METHODS, "os"):
        sim, ana = [], []
        for c in sweep:
            if c["method"] != method:
                continue
            for s, a in zip(c["sim_tilt_deg"], c["analytic_tilt_deg"]):
                if abs(a) > 1e-7:
                    sim.append(abs(s))
                    ana.append(abs(a))
        ax.loglog(ana, sim, marker, markersize=3, linestyle="none", label=method, alpha=0.6)
    ax.plot([1e-6, 10], [1e-6, 10], "k-", linewidth=0.8)
    ax.plot([1e-6, 10], [1.05e-6, 10.5], "k:", linewidth=0.8)
    ax.plot([1e-6, 10], [0.95e-6, 9.5], "k:", linewidth=0.8, label="+-5 %")
    ax.set_xlabel("|analytic tilt| [deg]")
    ax.set_ylabel("|simulated tilt| [deg]")
    ax.set_title("Simulated vs analytic tilt (N, E, D)")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "align_agreement.png"), dpi=120)
    plt.close(fig)


def fine_figure(traces, out_dir):
    grades = sorted({t["grade"] for t in traces}, key=lambda g: g != "tactical")
    fig, axes = plt.subplots(1, len(grades), figsize=(11, 4.5))
    if len(grades) == 1:
        axes = [axes]
    for ax, grade in zip(axes, grades):
        for t in (t for t in traces if t["grade"] == grade):
            dev = [e - t["limit_deg"] for e in t["heading_err_deg"]]
            ax.plot(t["t_s"], dev, linewidth=0.9, label=f"run {t['run']}")
        ax.axhline(0.0, color="k", linewidth=0.8)
        ax.set_title(f"{grade}: heading error minus gyrocompass limit")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("[deg]")
        ax.grid(True, alpha=0.3)
    axes[-1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "align_fine_heading.png"), dpi=120)
    plt.close(fig)


def main():
    out_dir = sys.argv[1]
    with open(os.path.join(out_dir, "align_sweep.json")) as f:
        sweep = json.load(f)
    sweep_figures(sweep, out_dir)
    agreement_figure(sweep, out_dir)
    fine_path = os.path.join(out_dir, "align_fine.json")
    if os.path.exists(fine_path):
        with open(fine_path) as f:
            fine_figure(json.load(f), out_dir)


if __name__ == "__main__":
    main()
