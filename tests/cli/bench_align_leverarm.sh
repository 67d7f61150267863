#!/usr/bin/env bash
# End-to-end: `deepnav bench align` and `deepnav bench leverarm` run, write JSON, and show
# the papers' findings; bad options are refused with a non-zero exit.
# Usage: bench_align_leverarm.sh DEEPNAV_BINARY SOURCE_DIR
set -euo pipefail
deepnav="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$deepnav" bench align --runs 1 --json "$work/align.json" > "$work/align.txt"
"$deepnav" bench leverarm --runs 2 --json "$work/leverarm.json" > "$work/leverarm.txt"
grep -q "one-shot pitch error at 1 deg/h z-gyro" "$work/align.txt"
grep -q "Table 1" "$work/leverarm.txt"

python3 - "$work/align.json" "$work/leverarm.json" <<'PY'
import json, sys
align = json.load(open(sys.argv[1]))
coarse = align["reports"][0]
pitch = coarse["notes"]["one-shot pitch error at 1 deg/h z-gyro (paper: about 2.3 deg)"]
assert 2.1 < abs(pitch) < 2.5, pitch
small = coarse["notes"]["worst difference in the small-angle region, gyro <= 0.3 deg/h (two-step, one-shot) %"]
assert max(small) < 5.0, small
for row in coarse["rows"]:
    if row["method"] == "two-step" and row["source"].startswith("gyro"):
        assert abs(row["sim_E"]) < 1e-9, row  # two-step east tilt has no gyro error
rest = {r["case"]: r for r in align["reports"][1]["rows"]}
assert rest["at rest"]["attitude"] == "returned"
assert rest["turning 1 deg/s"]["attitude"] == "withheld"
lever = json.load(open(sys.argv[2]))
rows = lever["reports"][0]["rows"]
conv = [r["ours_conv"] for r in rows]
prop = [r["ours_prop"] for r in rows]
assert all(b > a for a, b in zip(conv, conv[1:])), conv
assert all(p < c for p, c in zip(prop, conv)), (prop, conv)
assert max(prop) < 1.2 * min(prop), prop
full = lever["reports"][2]["rows"]
assert full[0]["observable"] == "yes" and full[1]["observable"] == "no", full
PY

if "$deepnav" bench leverarm --runs 0 > /dev/null 2>&1; then
  echo "expected --runs 0 to be refused" >&2
  exit 1
fi
echo "bench align/leverarm: ok"
