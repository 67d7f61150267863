"""cli.receiver_week: every product of a run dated by the signal's week.

  python3 -m checks.receiver_week RUN_DIR WEEK YYYY-MM-DD

pvt.csv's weeks, obs.rnx's first observation and epochs, the NMEA RMC dates, the GPX times
and nav.rnx's records all say that week and day.
"""
import sys
from pathlib import Path

import products
from checklist import CheckList


def main():
    run, week, day = Path(sys.argv[1]), sys.argv[2], sys.argv[3]
    year, month, dom = day.split("-")
    checks = CheckList()
    rows = products.pvt(run)
    checks.check("pvt.csv has fixes", bool(rows), len(rows))
    weeks = {r["gps_week"] for r in rows}
    checks.check(f"pvt.csv: week {week} only", weeks == {week}, weeks)
    obs = (run / "obs.rnx").read_text().splitlines()
    first = [line for line in obs if "TIME OF FIRST OBS" in line]
    checks.check(f"obs.rnx: first observation on {day}",
                 bool(first) and first[0].split()[:3] == [year, str(int(month)), str(int(dom))], first)
    epochs = [line for line in obs if line.startswith(">")]
    checks.check(f"obs.rnx: every epoch on {day}", bool(epochs) and all(e.startswith(f"> {year} {month} {dom}") for e in epochs),
                 epochs[:1])
    rmc = [line for line in open(run / "fixes.nmea") if line.startswith(("$GPRMC", "$GNRMC"))]
    nmea_day = f"{dom}{month}{year[2:]}"
    checks.check(f"NMEA: every RMC dated {nmea_day}", bool(rmc) and all(line.split(",")[9] == nmea_day for line in rmc),
                 [line.split(",")[9] for line in rmc[:2]])
    gpx = (run / "track.gpx").read_text()
    checks.check(f"GPX: every time on {day}",
                 f"<time>{day}T" in gpx and gpx.count("<time>") == gpx.count(f"<time>{day}T"))
    records = [line for line in (run / "nav.rnx").read_text().splitlines() if line.startswith("G")]
    checks.check(f"nav.rnx: every record on {day}",
                 bool(records) and all(f" {year} {month} {dom} " in line for line in records), records[:1])
    checks.exit()


if __name__ == "__main__":
    main()
