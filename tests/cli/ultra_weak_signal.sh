#!/usr/bin/env bash
# Ultra-tight on a weak signal (`bench threshold --modes ultra`, the land circle with a
# tactical IMU, C/N0 45 dB-Hz until 25 s then falling 0.5 dB/s to 5 dB-Hz): with the data
# bits wiped off and 200 ms coherent integrations it keeps a 10 m solution from at least
# four satellites' measurements to 13 dB-Hz or below (the scalar loops lose it near 29); the
# report names the integration used; a coherent length that is not a multiple of a data
# bit is rejected.
#   usage: ultra_weak_signal.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
check() { if eval "$2"; then echo "ok   $1"; else echo "FAIL $1"; fail=1; fi; }
ramp=(bench threshold --modes ultra --start 45 --ramp-start 25 --end 5 --rate 0.5 --work-dir "$work")
"$deepnav" -q "${ramp[@]}" --json "$work/long.json" > "$work/long.txt" || { cat "$work/long.txt"; echo "FAIL long run"; exit 1; }
msg=$("$deepnav" "${ramp[@]}" --coherent-ms 50 2>&1); rc=$?
check "--coherent-ms 50 rejected (exit $rc)" '[ $rc -ne 0 ] && grep -q "multiple of 20 ms" <<< "$msg"'
python3 - "$work" <<'PY' || fail=1
import json, sys
work = sys.argv[1]
def load(name):
    j = json.load(open(f"{work}/{name}.json"))
    return j["rows"][0], j["notes"]
good = True
def ok(name, cond, value):
    global good
    print(("ok   " if cond else "FAIL ") + name, value)
    good &= cond
long_row, long_notes = load("long")
ok("200 ms data-wiped: holds to 13 dB-Hz or below", long_row["threshold_dbhz"] <= 13.0, long_row)
ok("within 10 m while it holds", long_row["max_h_error_before_m"] < 10.0, long_row["max_h_error_before_m"])
ok("the report names the coherent length", long_notes["coherent_ms"] == 200 and "200 ms coherent" in long_notes["ultra_integration"],
   long_notes["ultra_integration"])
sys.exit(0 if good else 1)
PY
exit $fail
