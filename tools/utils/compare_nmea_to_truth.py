#!/usr/bin/env python3
"""Compares the GGA fixes of an NMEA file with a deepnav truth.csv (static or moving).

Each GGA fix is matched to the truth row of the same GPS second of day (NMEA time is
UTC: the GPS-UTC leap-second offset is given by --leap-seconds, 18 s in 2022). Prints
fix count and horizontal/vertical/3-D error statistics; exits 1 if any fix after the
first --skip ones is farther than --max-error-m from the truth, 2 if there are no fixes.
"""
import argparse
import csv
import math
import sys

A = 6378137.0
F = 1 / 298.257223563
E2 = F * (2 - F)


def llh_to_ecef(lat, lon, h):
    lat, lon = math.radians(lat), math.radians(lon)
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    return ((n + h) * math.cos(lat) * math.cos(lon), (n + h) * math.cos(lat) * math.sin(lon),
            (n * (1 - E2) + h) * math.sin(lat))


def ned(dx, lat, lon):
    lat, lon = math.radians(lat), math.radians(lon)
    sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
    n = -sl * co * dx[0] - sl * so * dx[1] + cl * dx[2]
    e = -so * dx[0] + co * dx[1]
    d = -cl * co * dx[0] - cl * so * dx[1] - sl * dx[2]
    return n, e, d


def parse_gga(path):
    fixes = []
    with open(path, errors="replace") as f:
        for line in f:
            p = line.strip().split(",")
            if len(p) < 10 or not p[0].endswith("GGA") or p[6] in ("", "0") or not p[2]:
                continue
            hh, mm, ss = int(p[1][0:2]), int(p[1][2:4]), float(p[1][4:])
            lat = int(p[2][:2]) + float(p[2][2:]) / 60 * 1
            lat = -lat if p[3] == "S" else lat
            lon = int(p[4][:3]) + float(p[4][3:]) / 60
            lon = -lon if p[5] == "W" else lon
            h = float(p[9]) + (float(p[11]) if len(p) > 11 and p[11] else 0.0)
            fixes.append((hh * 3600 + mm * 60 + ss, lat, lon, h))
    return fixes


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("nmea")
    ap.add_argument("truth")
    ap.add_argument("--leap-seconds", type=float, default=18.0)
    ap.add_argument("--max-error-m", type=float, default=10.0)
    ap.add_argument("--skip", type=int, default=5, help="first fixes not held to the bound (filter start-up)")
    a = ap.parse_args()
    truth = {}
    with open(a.truth) as f:
        for row in csv.DictReader(f):
            sod = round(float(row["gps_sow"]) % 86400.0, 3)
            truth[sod] = (float(row["x_ecef_m"]), float(row["y_ecef_m"]), float(row["z_ecef_m"]))
    fixes = parse_gga(a.nmea)

    def errors(leap):
        out = []
        for sod_utc, lat, lon, h in fixes:
            sod = round((sod_utc + leap) % 86400.0, 3)
            if sod not in truth:
                continue
            x = llh_to_ecef(lat, lon, h)
            t = truth[sod]
            n, e, d = ned([x[i] - t[i] for i in range(3)], lat, lon)
            out.append((math.hypot(n, e), abs(d), math.sqrt(n * n + e * e + d * d)))
        return out

    # Some receivers stamp NMEA with GPS time instead of UTC: use whichever offset
    # matches more fixes to truth epochs, and say which.
    errs = errors(a.leap_seconds)
    alt = errors(0.0)
    if len(alt) > len(errs):
        print("NMEA time stamps match truth as GPS time (no leap seconds)")
        errs = alt
    if not errs:
        print(f"no GGA fix of {a.nmea} matches a truth epoch of {a.truth}", file=sys.stderr)
        return 2
    judged = errs[a.skip:] if len(errs) > a.skip else errs
    rms = lambda v: math.sqrt(sum(x * x for x in v) / len(v))
    print(f"fixes compared: {len(errs)} (judged {len(judged)})")
    print(f"horizontal error: rms {rms([e[0] for e in judged]):.2f} m, max {max(e[0] for e in judged):.2f} m")
    print(f"vertical error:   rms {rms([e[1] for e in judged]):.2f} m, max {max(e[1] for e in judged):.2f} m")
    worst = max(e[2] for e in judged)
    print(f"3-D error:        rms {rms([e[2] for e in judged]):.2f} m, max {worst:.2f} m (bound {a.max_error_m} m)")
    return 0 if worst <= a.max_error_m else 1


if __name__ == "__main__":
    sys.exit(main())
