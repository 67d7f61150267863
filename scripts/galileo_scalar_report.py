#!/usr/bin/python3
"""Summarises the points of scripts/galileo_scalar_sweep.sh: per scenario, the horizontal RMS of
the scalar fix from GPS alone, Galileo alone and GPS+Galileo over the seeds (mean, spread,
worst), the ratios the Galileo issue asks for and how many seeds meet them; writes
OUT/summary.md (a Markdown table), OUT/summary.json and OUT/horizontal_rms.png.

    python3 scripts/galileo_scalar_report.py OUT
"""
import glob
import json
import statistics
import sys

CONFIGS = [("gps", "GPS"), ("galileo", "Galileo"), ("gps_galileo", "GPS+Galileo")]


def load(out):
    points = {}
    for path in sorted(glob.glob(f"{out}/points/*.json")):
        p = json.load(open(path))
        points.setdefault(p["scenario"], []).append(p)
    if not points:
        sys.exit(f"galileo_scalar_report.py: no point in {out}/points (run scripts/galileo_scalar_sweep.sh first)")
    return points


def summarise(points):
    summary = {}
    for scenario, runs in sorted(points.items()):
        s = {"seeds": sorted(p["seed"] for p in runs)}
        for key, _ in CONFIGS:
            h = [p["runs"][key]["horizontal_rms_m"] for p in runs]
            s[key] = {"horizontal_rms_mean_m": statistics.mean(h),
                      "horizontal_rms_sd_m": statistics.stdev(h) if len(h) > 1 else 0.0,
                      "horizontal_rms_max_m": max(h),
                      "pdop_mean": statistics.mean(p["runs"][key]["pdop_rms"] for p in runs),
                      "satellites_mean": statistics.mean(p["runs"][key]["satellites_used_rms"] for p in runs)}
        ratio = [p["runs"]["galileo"]["horizontal_rms_m"] / p["runs"]["gps"]["horizontal_rms_m"] for p in runs]
        s["galileo_over_gps_mean"] = statistics.mean(ratio)
        s["galileo_within_1_2x_gps_seeds"] = sum(r <= 1.2 for r in ratio)
        s["both_better_than_gps_seeds"] = sum(
            p["runs"]["gps_galileo"]["horizontal_rms_m"] < p["runs"]["gps"]["horizontal_rms_m"] for p in runs)
        summary[scenario] = s
    return summary


def table(summary):
    lines = ["| scenario | seeds | GPS H RMS (m) | Galileo H RMS (m) | GPS+Galileo H RMS (m) | PDOP G / E / G+E "
             "| satellites G / E / G+E | Galileo / GPS | Galileo <= 1.2x GPS | G+E < GPS |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for scenario, s in summary.items():
        n = len(s["seeds"])
        cell = [f"{s[k]['horizontal_rms_mean_m']:.2f} +- {s[k]['horizontal_rms_sd_m']:.2f} (max {s[k]['horizontal_rms_max_m']:.2f})"
                for k, _ in CONFIGS]
        pdop = " / ".join(f"{s[k]['pdop_mean']:.2f}" for k, _ in CONFIGS)
        sats = " / ".join(f"{s[k]['satellites_mean']:.1f}" for k, _ in CONFIGS)
        lines.append(f"| {scenario} | {n} | {cell[0]} | {cell[1]} | {cell[2]} | {pdop} | {sats} | "
                     f"{s['galileo_over_gps_mean']:.2f} | {s['galileo_within_1_2x_gps_seeds']} of {n} | "
                     f"{s['both_better_than_gps_seeds']} of {n} |")
    return "\n".join(lines) + "\n"


def plot(summary, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenarios = list(summary)
    fig, ax = plt.subplots(figsize=(10, 4.5))
    width = 0.27
    for i, (key, label) in enumerate(CONFIGS):
        x = [j + (i - 1) * width for j in range(len(scenarios))]
        ax.bar(x, [summary[s][key]["horizontal_rms_mean_m"] for s in scenarios], width,
               yerr=[summary[s][key]["horizontal_rms_sd_m"] for s in scenarios], capsize=3, label=label)
    ax.set_xticks(range(len(scenarios)))
    ax.set_xticklabels([s.replace("_gps_galileo", "").replace("_60s", "") for s in scenarios])
    ax.set_ylabel("horizontal RMS (m), mean +- sd over seeds")
    ax.set_title("Scalar fix: GPS alone, Galileo alone, both (synthesized IF, 4 Msps)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    summary = summarise(load(out))
    json.dump(summary, open(f"{out}/summary.json", "w"), indent=1)
    text = table(summary)
    open(f"{out}/summary.md", "w").write(text)
    plot(summary, f"{out}/horizontal_rms.png")
    sys.stdout.write(text)


if __name__ == "__main__":
    main()
