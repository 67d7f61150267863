#!/usr/bin/env python3
"""Ultra-tight weak-signal threshold against the coherent length, per oscillator and IMU.

Reads the `deepnav bench threshold --modes ultra --coherent-ms N --json` reports of a folder
(files ultra_<imu>_<oscillator>_c<N>.json), writes coherent.md (a table) and coherent.png.
    usage: plot_threshold_coherent.py FOLDER
"""
import glob
import json
import os
import re
import sys


def main(folder):
    runs = {}
    for path in sorted(glob.glob(os.path.join(folder, "ultra_*_c*.json"))):
        m = re.match(r"ultra_(.+)_(tcxo|ocxo|ideal)_c(\d+)\.json$", os.path.basename(path))
        if not m:
            continue
        report = json.load(open(path))
        row = report["rows"][0]
        runs.setdefault((m.group(1), m.group(2)), {})[int(m.group(3))] = (row["threshold_dbhz"], row["failure"],
                                                                        row["max_h_error_before_m"])
    if not runs:
        sys.exit(f"{folder}: no ultra_<imu>_<oscillator>_c<ms>.json reports")
    lengths = sorted({c for v in runs.values() for c in v})
    lines = ["| IMU | oscillator | " + " | ".join(f"{c} ms" for c in lengths) + " |",
             "|---|---|" + "---|" * len(lengths)]
    for (imu, osc), v in sorted(runs.items()):
        cells = []
        for c in lengths:
            if c not in v:
                cells.append("")
                continue
            thr, failure, h = v[c]
            mark = " (10 m)" if failure.startswith("horizontal error") else ""
            cells.append(f"{thr:.2f}{mark}")
        lines.append(f"| {imu} | {osc} | " + " | ".join(cells) + " |")
    lines.append("")
    lines.append("First C/N0 (dB-Hz) at which ultra-tight stops holding a 10 m solution from four satellites' "
                 "measurements, by coherent length with the data wiped off (20 ms: no wipe-off); \"(10 m)\": "
                 "it failed by the error bound, not by coasting.")
    with open(os.path.join(folder, "coherent.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not available: no plot", file=sys.stderr)
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for (imu, osc), v in sorted(runs.items()):
        cs = sorted(v)
        ax.plot(cs, [v[c][0] for c in cs], marker="o", label=f"{imu}, {osc}")
    ax.set_xscale("log")
    ax.set_xticks(lengths)
    ax.set_xticklabels([str(c) for c in lengths])
    ax.set_xlabel("coherent length (ms, data wiped off; 20: bit-edge-limited)")
    ax.set_ylabel("threshold (dB-Hz, lower is better)")
    ax.set_title("Ultra-tight threshold on the land circle against coherent length")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "coherent.png"), dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
