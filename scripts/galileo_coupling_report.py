#!/usr/bin/python3
"""GPS alone against GPS+Galileo in the aided modes, paired run by run.

Reads the points of `deepnav bench coupling --systems gps` and `--systems gps,galileo`
sweeps made on the same mixed scenario (the same seeds, so the same IF for both receivers)
and writes, per error world and mode, each system set's horizontal and 3-D RMS (mean and
standard deviation over the runs of each run's RMS from --from-s to the end), the paired
difference and how many runs GPS+Galileo did better; a markdown table and a PNG.

    scripts/galileo_coupling_report.py results/galileo_coupling
reads DIR/<world>/gps/points/*.json and DIR/<world>/gps_galileo/points/*.json and writes
DIR/table.md and DIR/rms.png.
"""
import argparse
import glob
import json
import math
import os
import sys

MODES = ["loose", "tight", "ultra"]
SYSTEMS = [("gps", "GPS"), ("gps_galileo", "GPS+Galileo")]


def run_rms(epochs, from_s):
    """Horizontal and 3-D RMS of the valid epochs from from_s on (t, mode, valid, n, e, d, v)."""
    h2 = d3 = 0.0
    n = 0
    for t, _mode, valid, en, ee, ed, _v in epochs:
        if t < from_s or not valid:
            continue
        h2 += en * en + ee * ee
        d3 += en * en + ee * ee + ed * ed
        n += 1
    if n == 0:
        return None
    return math.sqrt(h2 / n), math.sqrt(d3 / n)


def load_sweep(folder, from_s):
    """{(trajectory, run): {mode: (rms_h, rms_3d)}} of a sweep's finished points."""
    out = {}
    for path in sorted(glob.glob(os.path.join(folder, "points", "*.json"))):
        with open(path) as f:
            point = json.load(f)
        key = (point["trajectory"], point["run"])
        out[key] = {}
        for mode, record in point["modes"].items():
            rms = run_rms(record["epochs"], from_s)
            if rms is not None:
                out[key][mode] = rms
    return out


def mean_std(values):
    if not values:
        return float("nan"), float("nan")
    m = sum(values) / len(values)
    s = math.sqrt(sum((v - m) ** 2 for v in values) / (len(values) - 1)) if len(values) > 1 else 0.0
    return m, s


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("folder")
    ap.add_argument("--from-s", type=float, default=30.0, help="RMS from this time to the end (s)")
    ap.add_argument("--worlds", default="open-sky,suburban")
    a = ap.parse_args()

    rows = []
    for world in a.worlds.split(","):
        sweeps = {}
        for key, _label in SYSTEMS:
            folder = os.path.join(a.folder, world, key)
            if not os.path.isdir(folder):
                sys.exit(f"{folder}: no such sweep folder (expected DIR/<world>/gps and DIR/<world>/gps_galileo)")
            sweeps[key] = load_sweep(folder, a.from_s)
        runs = sorted(set(sweeps["gps"]) & set(sweeps["gps_galileo"]))
        for mode in MODES:
            pairs = [(sweeps["gps"][r][mode], sweeps["gps_galileo"][r][mode]) for r in runs
                     if mode in sweeps["gps"][r] and mode in sweeps["gps_galileo"][r]]
            if not pairs:
                continue
            row = {"world": world, "mode": mode, "runs": len(pairs)}
            for i, what in ((0, "h"), (1, "3d")):
                g = [p[0][i] for p in pairs]
                ge = [p[1][i] for p in pairs]
                row[f"gps_{what}"] = mean_std(g)
                row[f"both_{what}"] = mean_std(ge)
                row[f"diff_{what}"] = mean_std([y - x for x, y in zip(g, ge)])
                row[f"better_{what}"] = sum(1 for x, y in zip(g, ge) if y < x)
            rows.append(row)
    if not rows:
        sys.exit(f"{a.folder}: no finished pairs of points")

    def ms(v):
        return f"{v[0]:.2f} ± {v[1]:.2f}"

    lines = [
        "| world | mode | runs | horizontal RMS GPS (m) | horizontal RMS GPS+Galileo (m) | paired difference (m) "
        "| GPS+Galileo better | 3-D RMS GPS (m) | 3-D RMS GPS+Galileo (m) | paired difference (m) | GPS+Galileo better |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['world']} | {r['mode']} | {r['runs']} | {ms(r['gps_h'])} | {ms(r['both_h'])} | {ms(r['diff_h'])} "
            f"| {r['better_h']}/{r['runs']} | {ms(r['gps_3d'])} | {ms(r['both_3d'])} | {ms(r['diff_3d'])} "
            f"| {r['better_3d']}/{r['runs']} |")
    table = "\n".join(lines) + "\n"
    with open(os.path.join(a.folder, "table.md"), "w") as f:
        f.write(f"Each run's RMS from {a.from_s:g} s to the end; mean ± standard deviation over the runs; "
                "paired difference = GPS+Galileo minus GPS on the same IF.\n\n" + table)
    print(table, end="")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    worlds = sorted(set(r["world"] for r in rows), key=a.worlds.split(",").index)
    fig, axes = plt.subplots(1, len(worlds), figsize=(5 * len(worlds), 4), squeeze=False)
    for ax, world in zip(axes[0], worlds):
        wr = [r for r in rows if r["world"] == world]
        x = range(len(wr))
        for k, (key, label) in enumerate((("gps_h", "GPS"), ("both_h", "GPS+Galileo"))):
            ax.bar([i + 0.38 * k for i in x], [r[key][0] for r in wr], 0.36, yerr=[r[key][1] for r in wr],
                   capsize=3, label=label)
        ax.set_xticks([i + 0.19 for i in x])
        ax.set_xticklabels([r["mode"] for r in wr])
        ax.set_ylabel("horizontal RMS (m)")
        ax.set_title(f"land circle, {world}, {wr[0]['runs']} runs")
        ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(a.folder, "rms.png"), dpi=110)


if __name__ == "__main__":
    main()
