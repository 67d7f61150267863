"""cli.bench_align_leverarm: the papers' findings in `deepnav bench align` and `bench leverarm`.

  python3 -m checks.bench_align_leverarm ALIGN_JSON LEVERARM_JSON
"""
import sys

from checklist import CheckList
from products import read_json


def check_align(checks, align):
    coarse = align["reports"][0]
    pitch = coarse["notes"]["one-shot pitch error at 1 deg/h z-gyro (paper: about 2.3 deg)"]
    checks.check("align: one-shot pitch error at 1 deg/h z-gyro about 2.3 deg", 2.1 < abs(pitch) < 2.5, pitch)
    small = coarse["notes"]["worst difference in the small-angle region, gyro <= 0.3 deg/h (two-step, one-shot) %"]
    checks.check("align: two-step and one-shot within 5 % for small gyro errors", max(small) < 5.0, small)
    two_step_gyro = [row for row in coarse["rows"] if row["method"] == "two-step" and row["source"].startswith("gyro")]
    checks.check("align: two-step east tilt has no gyro error (rows there)",
                 bool(two_step_gyro) and all(abs(row["sim_E"]) < 1e-9 for row in two_step_gyro),
                 [row["sim_E"] for row in two_step_gyro])
    rest = {r["case"]: r for r in align["reports"][1]["rows"]}
    checks.check("align: attitude returned at rest, withheld turning at 1 deg/s",
                 rest["at rest"]["attitude"] == "returned" and rest["turning 1 deg/s"]["attitude"] == "withheld",
                 (rest["at rest"]["attitude"], rest["turning 1 deg/s"]["attitude"]))


def check_leverarm(checks, lever):
    rows = lever["reports"][0]["rows"]
    conv = [r["ours_conv"] for r in rows]
    prop = [r["ours_prop"] for r in rows]
    checks.check("leverarm: the conventional error grows down the table", all(b > a for a, b in zip(conv, conv[1:])),
                 conv)
    checks.check("leverarm: the proposed error below the conventional on every row",
                 all(p < c for p, c in zip(prop, conv)), (prop, conv))
    checks.check("leverarm: the proposed error about constant (within 20 %)", max(prop) < 1.2 * min(prop), prop)
    full = lever["reports"][2]["rows"]
    checks.check("leverarm: observable in the first case, not in the second",
                 full[0]["observable"] == "yes" and full[1]["observable"] == "no", full)


def main():
    checks = CheckList()
    check_align(checks, read_json(sys.argv[1]))
    check_leverarm(checks, read_json(sys.argv[2]))
    checks.exit()


if __name__ == "__main__":
    main()
