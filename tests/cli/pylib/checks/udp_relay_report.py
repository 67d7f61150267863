"""cli.stream_udp_impaired: the relay (peers/udp_impair.py) did what the test asked of it,
so that comparing its report with the receiver's tests the receiver, not the relay.

  python3 -m checks.udp_relay_report RELAY_JSON
"""
import sys

from checklist import CheckList
from products import read_json

SAMPLES_PER_FRAME = 4096  # 8192-byte ibyte frames


def main():
    r = read_json(sys.argv[1])
    dropped = {d["sequence"] for d in r["dropped"]}
    duplicated = {d["sequence"] for d in r["duplicated"]}
    reordered = {x["sequence"]: x["displacement"] for x in r["reordered"]}
    checks = CheckList("relay")
    checks.check("the stream ended normally", r["ended_by"] == "end of stream", r["ended_by"])
    checks.check("2998 frames from the server", r["frames_from_server"] == 2998, r["frames_from_server"])
    checks.check("dropped 5-7, 100 and the last frame 2997 (288 samples)",
                 {5, 6, 7, 100, 2997} <= dropped
                 and r["dropped"][-1] == {"sequence": 2997, "first_sample": 2997 * SAMPLES_PER_FRAME, "samples": 288},
                 sorted(dropped))
    checks.check("duplicated 40, 41, 200", {40, 41, 200} <= duplicated, sorted(duplicated))
    checks.check("reordered 300:1, 400:5, 500:63, 700:64",
                 all(reordered.get(s) == k for s, k in {300: 1, 400: 5, 500: 63, 700: 64}.items()), reordered)
    checks.check("seeded impairments besides the explicit ones",
                 len(dropped) > 5 and len(duplicated) > 3 and len(reordered) > 4,
                 (len(dropped), len(duplicated), len(reordered)))
    checks.exit()


if __name__ == "__main__":
    main()
