#!/usr/bin/env python3
"""Ultra-tight against tight under delay model mismatches: a Markdown table and a PNG.

  plot_mismatch.py --case LABEL BEFORE.json AFTER.json [--case ...] --png OUT.png

Each JSON is what `deepnav bench coupling --json` writes for one mismatch case (the same
points scored before and after a change). Prints, per case and trajectory, tight's and
ultra-tight's mean horizontal RMS before and after, ultra-tight minus tight paired over
the runs (mean +- standard deviation, and the bench's verdict), and the vertical RMS from
10 s after the detection; the PNG draws the paired differences with their spread.
"""
import argparse
import json
import math
import sys


def load(path):
    with open(path, encoding="utf-8") as f:
        report = json.load(f)
    rows = {(r["trajectory"], r["mode"]): r for r in report["rows"]}
    paired = report["notes"].get("paired", {})
    return rows, paired


def fmt(x, digits=3):
    return "nan" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{digits}f}"


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--case", nargs=3, action="append", metavar=("LABEL", "BEFORE", "AFTER"), required=True)
    p.add_argument("--png", help="plot of the paired differences")
    a = p.parse_args()
    print("| mismatch | path | tight h before / now (m) | ultra h before / now (m) | ultra - tight now (m) "
          "| verdict | ultra - tight before (m) | v settled tight / ultra now (m) |")
    print("|---|---|---|---|---|---|---|---|")
    bars = []
    for label, before_path, after_path in a.case:
        before, before_pairs = load(before_path)
        after, after_pairs = load(after_path)
        for traj in sorted({t for t, _ in after}):
            d_now = after_pairs.get(traj, {}).get("ultra_minus_tight_h_m", {})
            d_before = before_pairs.get(traj, {}).get("ultra_minus_tight_h_m", {})
            print(f"| {label} | {traj} "
                  f"| {fmt(before[(traj, 'tight')]['rms_h_mean_m'])} / {fmt(after[(traj, 'tight')]['rms_h_mean_m'])} "
                  f"| {fmt(before[(traj, 'ultra')]['rms_h_mean_m'])} / {fmt(after[(traj, 'ultra')]['rms_h_mean_m'])} "
                  f"| {fmt(d_now.get('mean'))} +- {fmt(d_now.get('std'))} "
                  f"| {after_pairs.get(traj, {}).get('ultra_beats_tight_h', '-')} "
                  f"| {fmt(d_before.get('mean'))} +- {fmt(d_before.get('std'))} "
                  f"| {fmt(after[(traj, 'tight')]['rms_v_settled_m'], 2)} / "
                  f"{fmt(after[(traj, 'ultra')]['rms_v_settled_m'], 2)} |")
            bars.append((f"{label}\n{traj}", d_before, d_now))
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(9, 4))
        for i, (name, d_before, d_now) in enumerate(bars):
            for dx, d, color, what in ((-0.15, d_before, "tab:gray", "before"), (0.15, d_now, "tab:blue", "now")):
                if "mean" in d:
                    ax.errorbar(i + dx, d["mean"], yerr=d["std"], fmt="o", color=color, capsize=4,
                                label=what if i == 0 else None)
        ax.axhline(0.0, color="black", linewidth=0.8)
        ax.set_xticks(range(len(bars)))
        ax.set_xticklabels([b[0] for b in bars], fontsize=8)
        ax.set_ylabel("ultra-tight - tight horizontal RMS (m)")
        ax.set_title("Paired over 10 runs: mean and standard deviation (below 0: ultra-tight ahead)")
        ax.legend()
        fig.tight_layout()
        fig.savefig(a.png, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
