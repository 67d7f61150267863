#!/usr/bin/env bash
# `deepnav acquire` on the real 4 MHz capture: JSON output lists the expected PRNs
# with their Doppler and delay; a wrong sample rate is a plain error, non-zero exit.
#   usage: acquire_real_sky.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$deepnav" acquire --input "$src/data/L1_20211202_084700_4MHz_IQ.bin" --format ibyte --fs 4000000 \
  --inverted-spectrum --json "$work/acq.json" > "$work/table.txt" || { echo "FAIL acquire exit status"; exit 1; }
python3 - "$work/acq.json" <<'PY' || exit 1
import json, sys
doc = json.load(open(sys.argv[1]))
found = {r["prn"]: r for r in doc["results"] if r["detected"]}
expected = {31: (-190, 1159), 26: (650, 3599), 29: (-2220, 1653), 16: (2600, 3958), 32: (-3380, 2766)}
bad = []
for prn, (dop, delay) in expected.items():
    r = found.get(prn)
    if r is None or abs(r["doppler_hz"] - dop) > 250 or abs(r["delay_samples"] - delay) > 2:
        bad.append(f"PRN {prn}: {r}")
extra = set(found) - set(expected) - {18}
if extra:
    bad.append(f"unexpected PRNs {sorted(extra)}")
if len(doc["results"]) != 32:
    bad.append("JSON should list all 32 searched PRNs")
print("\n".join(bad) if bad else "ok: " + ", ".join(str(p) for p in sorted(found)))
sys.exit(1 if bad else 0)
PY
grep -q "^  31 " "$work/table.txt" || { echo "FAIL table lacks PRN 31"; cat "$work/table.txt"; exit 1; }
msg=$("$deepnav" acquire --input "$src/data/L1_20211202_084700_4MHz_IQ.bin" --format ibyte --fs 2500000 2>&1 >/dev/null)
rc=$?
[[ $rc -ne 0 && $msg == *"no satellite acquired"* ]] || { echo "FAIL wrong --fs: rc=$rc msg=$msg"; exit 1; }
msg=$("$deepnav" acquire --input "$src/data/L1_20211202_084700_4MHz_IQ.bin" --format int4 --fs 4000000 2>&1 >/dev/null)
[[ $? -ne 0 && $msg == *"--format"* ]] || { echo "FAIL bad --format: $msg"; exit 1; }
echo "ok"
