"""`deepnav acquire --json` of a real capture found its satellites:

  python3 -m checks.acquisition ACQ_JSON CAPTURE [--searched N] [--no-others-but PRN...]

every expected PRN of CAPTURE (captures.py) detected within the tolerances; --searched: the
JSON lists N searched PRNs; --no-others-but: no PRN detected beyond the expected and these.
"""
import argparse

from captures import DELAY_TOLERANCE_SAMPLES, DOPPLER_TOLERANCE_HZ, EXPECTED_ACQUISITIONS
from checklist import CheckList
from products import read_json


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("acquisition_json")
    parser.add_argument("capture", choices=sorted(EXPECTED_ACQUISITIONS))
    parser.add_argument("--searched", type=int)
    parser.add_argument("--no-others-but", type=int, nargs="*")
    args = parser.parse_args()
    doc = read_json(args.acquisition_json)
    expected = EXPECTED_ACQUISITIONS[args.capture]
    found = {r["prn"]: r for r in doc["results"] if r["detected"]}
    checks = CheckList(args.capture)
    print(f"{args.capture}: {doc['sample_rate_hz']} Hz, IF {doc['if_hz']} Hz; PRNs detected {sorted(found)}")
    for prn, (doppler_hz, delay_samples) in expected.items():
        r = found.get(prn)
        checks.check(f"PRN {prn} near {doppler_hz} Hz, {delay_samples} samples",
                     r is not None and abs(r["doppler_hz"] - doppler_hz) <= DOPPLER_TOLERANCE_HZ
                     and abs(r["delay_samples"] - delay_samples) <= DELAY_TOLERANCE_SAMPLES,
                     r and (round(r["doppler_hz"]), round(r["delay_samples"], 1)))
    if args.no_others_but is not None:
        others = sorted(set(found) - set(expected) - set(args.no_others_but))
        checks.check(f"no PRN detected but those and {args.no_others_but}", not others, others)
    if args.searched is not None:
        checks.check(f"{args.searched} PRNs searched", len(doc["results"]) == args.searched, len(doc["results"]))
    checks.exit()


if __name__ == "__main__":
    main()
