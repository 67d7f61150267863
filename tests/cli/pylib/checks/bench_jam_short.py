"""cli.bench_jam_short: the short jamming sweep's runs.csv and its ultra-tight point.

  python3 -m checks.bench_jam_short SWEEP_DIR
"""
import glob
import sys
from pathlib import Path

from checklist import CheckList
from products import read_csv, read_json


def main():
    folder = Path(sys.argv[1])
    runs = read_csv(folder / "runs.csv")
    rows = {(r["mode"], r["mitigation"], float(r["js_db"])): r for r in runs}
    checks = CheckList()
    checks.check("five points in runs.csv", len(rows) == 5 == len(runs), sorted(rows))
    r = rows[("scalar", "none", 20.0)]
    checks.check("J/S 20 dB, no mitigation: fix kept within 10 m", r["failed"] == "0" and float(r["horizontal_max_m"]) < 10,
                 (r["failed"], r["horizontal_max_m"], r["fix_availability"]))
    checks.check("J/S 20 dB: channels tracked", float(r["tracked_fraction_mean"]) > 0.9, r["tracked_fraction_mean"])
    r = rows[("scalar", "none", 60.0)]
    checks.check("J/S 60 dB, no mitigation: fails", r["failed"] == "1", (r["failure"], r["cn0_mean_dbhz"]))
    r = rows[("scalar", "excision", 60.0)]
    checks.check("J/S 60 dB, excision: fix kept within 10 m", r["failed"] == "0",
                 (r["failure"], r["horizontal_max_m"], r["cn0_mean_dbhz"]))
    checks.check("J/S 60 dB, excision: C/N0 above 35 dB-Hz", float(r["cn0_mean_dbhz"]) > 35, r["cn0_mean_dbhz"])
    r = rows[("ultra", "none", 20.0)]
    checks.check("ultra, J/S 20 dB: passes with every epoch a GNSS fix",
                 r["failed"] == "0" and float(r["fix_availability"]) == 1.0,
                 (r["failure"], r["fix_availability"], r["horizontal_max_m"]))
    checks.check("ultra, J/S 20 dB: the solution is the ultra-tight filter's throughout",
                 r["epochs_in_mode"].split() == ["ultra:6"], r["epochs_in_mode"])
    points = glob.glob(str(folder / "points" / "*_ultra_none_s1" / "point.json"))
    checks.check("one ultra-tight point folder", len(points) == 1, points)
    p = read_json(points[0])
    changes = [(c["from"], c["to"]) for c in p["mode_changes"]]
    checks.check("ultra point: one mode change scalar -> ultra before the onset",
                 changes == [("scalar", "ultra")] and p["mode_changes"][0]["t_s"] < 14, p["mode_changes"])
    checks.check("ultra point: run with the IMU and assisted ephemerides",
                 all(a in p["command"] for a in ("--mode ultra", "--imu ", "--imu-grade tactical",
                                                 "--imu-lever-arm 0.5 0 -0.3", "--ephemeris-from")), p["command"])
    checks.exit()


if __name__ == "__main__":
    main()
