"""Tracks of `deepnav fuse` runs and of a single-point solution over an RTKLIB reference.

Usage: /usr/bin/python3 tools/plots/plot_fuse.py REFERENCE.pos OUT.png LABEL=FILE [LABEL=FILE ...]
  FILE: an RTKLIB .pos solution (lat/lon/height) or a deepnav pvt.csv.

Each solution is compared with the reference on common epochs (within 10 ms) in the
reference's local east/north/up frame at its first epoch; its mean offset is removed (the
reference's base was not surveyed, see data/walk_0827/README.md), so the left panel shows
each track where it lies against the reference's shape, the right one the horizontal error
about that offset over time. The statistics printed are the ones `deepnav fuse --reference`
writes to summary.json.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

A, F = 6378137.0, 1.0 / 298.257223563
E2 = F * (2.0 - F)
SECONDS_PER_DAY = 86400.0
GPS_EPOCH_ORDINAL = 722820  # date(1980, 1, 6).toordinal()


def ecef(lat_deg, lon_deg, h):
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = A / math.sqrt(1.0 - E2 * math.sin(lat) ** 2)
    return ((n + h) * math.cos(lat) * math.cos(lon), (n + h) * math.cos(lat) * math.sin(lon),
            (n * (1.0 - E2) + h) * math.sin(lat))


def read_pos(path):
    """{GPS seconds since 1980 (rounded to 1 ms): ECEF} of an RTKLIB .pos file (GPST, lat/lon/height)."""
    import datetime
    out = {}
    for line in open(path):
        if line.startswith("%") or not line.strip():
            continue
        f = line.split()
        d = datetime.date(*(int(x) for x in f[0].split("/"))).toordinal() - GPS_EPOCH_ORDINAL
        h, m, s = f[1].split(":")
        t = d * SECONDS_PER_DAY + int(h) * 3600.0 + int(m) * 60.0 + float(s)
        out[round(t, 3)] = ecef(float(f[2]), float(f[3]), float(f[4]))
    return out


def read_pvt_csv(path):
    out = {}
    for r in csv.DictReader(open(path)):
        t = int(r["gps_week"]) * 7 * SECONDS_PER_DAY + float(r["gps_sow"])
        out[round(t, 3)] = (float(r["x_ecef_m"]), float(r["y_ecef_m"]), float(r["z_ecef_m"]))
    return out


def read_solution(path):
    return read_pvt_csv(path) if path.endswith(".csv") else read_pos(path)


def enu_frame(p):
    x, y, z = p
    lon = math.atan2(y, x)
    lat = math.atan2(z, math.hypot(x, y) * (1.0 - E2))
    for _ in range(5):
        n = A / math.sqrt(1.0 - E2 * math.sin(lat) ** 2)
        lat = math.atan2(z + E2 * n * math.sin(lat), math.hypot(x, y))
    sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
    return ((-so, co, 0.0), (-sl * co, -sl * so, cl), (cl * co, cl * so, sl))


def to_enu(frame, origin, p):
    d = [p[i] - origin[i] for i in range(3)]
    return tuple(sum(frame[r][i] * d[i] for i in range(3)) for r in range(3))


def match(solution, reference):
    """(t, solution ENU, reference ENU) on common epochs (within 10 ms)."""
    keys = sorted(reference)
    origin = reference[keys[0]]
    frame = enu_frame(origin)
    by_ms = {int(round(k * 1000.0)): k for k in keys}
    out = []
    for t in sorted(solution):
        ms = int(round(t * 1000.0))
        near = min((d for d in range(-10, 11) if ms + d in by_ms), key=abs, default=None)
        if near is None:
            continue
        out.append((t, to_enu(frame, origin, solution[t]), to_enu(frame, origin, reference[by_ms[ms + near]])))
    return out


def statistics(pairs):
    n = len(pairs)
    err = [[s[i] - r[i] for i in range(3)] for _, s, r in pairs]
    mean = [sum(e[i] for e in err) / n for i in range(3)]
    about = [[e[i] - mean[i] for i in range(3)] for e in err]
    h = [math.hypot(e[0], e[1]) for e in about]
    return dict(epochs=n, mean=mean, rms_h=math.sqrt(sum(e[0] ** 2 + e[1] ** 2 for e in err) / n),
                rms_3d=math.sqrt(sum(e[0] ** 2 + e[1] ** 2 + e[2] ** 2 for e in err) / n),
                scatter_h=math.sqrt(sum(x * x for x in h) / n), max_h=max(h),
                max_3d=max(math.sqrt(sum(x * x for x in e)) for e in about), about=about)


def main():
    if len(sys.argv) < 4 or any("=" not in a for a in sys.argv[3:]):
        sys.exit(__doc__)
    reference = read_pos(sys.argv[1])
    runs = [(a.split("=", 1)[0], read_solution(a.split("=", 1)[1])) for a in sys.argv[3:]]
    fig, (ax, ax_t) = plt.subplots(1, 2, figsize=(14, 6.5), gridspec_kw={"width_ratios": [1.1, 1.0]})
    keys = sorted(reference)
    frame, origin = enu_frame(reference[keys[0]]), reference[keys[0]]
    ref_enu = [to_enu(frame, origin, reference[k]) for k in keys]
    ax.plot([p[0] for p in ref_enu], [p[1] for p in ref_enu], color="black", lw=2.2, label="RTK reference", zorder=1)
    print("%-28s %6s %22s %8s %10s %7s %7s" % ("solution", "epochs", "mean offset E,N,U (m)", "RMS H", "scatter H",
                                                "max H", "max 3-D"))
    colors = ["tab:gray", "tab:blue", "tab:red", "tab:green", "tab:orange", "tab:purple", "tab:brown", "tab:olive"]
    if len(runs) > len(colors):
        sys.exit("at most %d solutions in one plot" % len(colors))
    t0 = keys[0]
    for (label, sol), color in zip(runs, colors):
        pairs = match(sol, reference)
        if not pairs:
            sys.exit("%s: no epoch in common with the reference" % label)
        st = statistics(pairs)
        print("%-28s %6d %22s %8.3f %10.3f %7.2f %7.2f" % (label, st["epochs"], "%.2f, %.2f, %.2f" % tuple(st["mean"]),
                                                         st["rms_h"], st["scatter_h"], st["max_h"], st["max_3d"]))
        ax.plot([s[0] - st["mean"][0] for _, s, _ in pairs], [s[1] - st["mean"][1] for _, s, _ in pairs], color=color,
                lw=1.0, alpha=0.85, label="%s (scatter %.2f m)" % (label, st["scatter_h"]), zorder=2)
        ax_t.plot([t - t0 for t, _, _ in pairs], [math.hypot(e[0], e[1]) for e in st["about"]], color=color, lw=1.0,
                  label=label)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("east (m)")
    ax.set_ylabel("north (m)")
    ax.set_title("tracks, each less its mean offset from the reference")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    ax_t.set_xlabel("time since the first reference epoch (s)")
    ax_t.set_ylabel("horizontal error about the mean offset (m)")
    ax_t.set_title("horizontal error over time")
    ax_t.grid(alpha=0.3)
    ax_t.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)
    print("wrote %s" % sys.argv[2])


if __name__ == "__main__":
    main()
