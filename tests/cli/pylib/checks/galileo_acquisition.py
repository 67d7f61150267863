"""`deepnav acquire --systems gps,galileo --json` of a real capture:

  python3 -m checks.galileo_acquisition SYSTEMS_JSON GPS_ONLY_JSON CAPTURE [--gps-also PRN...]

every result names its system and PRN; the GPS results are those of `deepnav acquire` without
--systems (GPS_ONLY_JSON) field for field, 32 PRNs searched, the expected ones found and no
others but --gps-also; 36 Galileo SVIDs searched, the expected ones (captures.py, cross-checked
with GNSS-SDR) found within a Doppler bin and the delay tolerance, and no others.
"""
import argparse

from captures import (DELAY_TOLERANCE_SAMPLES, EXPECTED_ACQUISITIONS, EXPECTED_GALILEO_ACQUISITIONS,
                      GALILEO_DOPPLER_TOLERANCE_HZ)
from checklist import CheckList
from products import read_json


def delay_error(a, b, period):
    d = abs(a - b) % period
    return min(d, period - d)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("systems_json")
    parser.add_argument("gps_only_json")
    parser.add_argument("capture", choices=sorted(EXPECTED_GALILEO_ACQUISITIONS))
    parser.add_argument("--gps-also", type=int, nargs="*", default=[])
    args = parser.parse_args()
    doc = read_json(args.systems_json)
    gps_only = read_json(args.gps_only_json)
    checks = CheckList(args.capture)
    results = doc["results"]
    checks.check("systems listed", doc.get("systems") == ["gps", "galileo"], doc.get("systems"))
    checks.check("every result names its system and PRN",
                 all(r.get("system") in ("gps", "galileo") and isinstance(r.get("prn"), int) for r in results))
    gps = [r for r in results if r.get("system") == "gps"]
    galileo = [r for r in results if r.get("system") == "galileo"]

    # GPS: unchanged by searching Galileo as well.
    stripped = [{k: v for k, v in r.items() if k not in ("system", "satellite")} for r in gps]
    checks.check("GPS results identical to a GPS-only run", stripped == gps_only["results"])
    checks.check("32 GPS PRNs searched", len(gps) == 32, len(gps))
    found = {r["prn"]: r for r in gps if r["detected"]}
    print(f"GPS detected {sorted(found)}")
    for prn, (doppler_hz, delay) in EXPECTED_ACQUISITIONS[args.capture].items():
        checks.check(f"G{prn:02d} found", prn in found)
    others = sorted(set(found) - set(EXPECTED_ACQUISITIONS[args.capture]) - set(args.gps_also))
    checks.check(f"no other GPS PRN but {args.gps_also}", not others, others)

    # Galileo: the satellites GNSS-SDR confirms, and no others.
    period = doc["sample_rate_hz"] * 4e-3
    checks.check("36 Galileo SVIDs searched", len(galileo) == 36, len(galileo))
    found = {r["prn"]: r for r in galileo if r["detected"]}
    print(f"Galileo detected {sorted(found)}")
    for svid, (doppler_hz, delay) in EXPECTED_GALILEO_ACQUISITIONS[args.capture].items():
        r = found.get(svid)
        checks.check(f"E{svid:02d} near {doppler_hz} Hz, {delay} samples",
                     r is not None and r["satellite"] == f"E{svid:02d}"
                     and abs(r["doppler_hz"] - doppler_hz) <= GALILEO_DOPPLER_TOLERANCE_HZ
                     and delay_error(r["delay_samples"], delay, period) <= DELAY_TOLERANCE_SAMPLES,
                     r and (round(r["doppler_hz"]), round(r["delay_samples"], 1), round(r["cn0_dbhz"], 1)))
    others = sorted(set(found) - set(EXPECTED_GALILEO_ACQUISITIONS[args.capture]))
    checks.check("no other Galileo SVID", not others, others)
    checks.exit()


if __name__ == "__main__":
    main()
