#!/usr/bin/env bash
# A short jamming sweep (30 s scenario at 2.6 Msps, CW from 25 s at J/S 20 and 60 dB,
# with and without excision, two jobs): the unmitigated receiver keeps its fix at 20 dB
# and loses it at 60 dB, excision keeps it at 60 dB; a second run finds every point
# finished; --list-commands prints one command per unfinished point; an unknown receiver
# mode is rejected naming the available ones.
#   usage: bench_jam_short.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sweep=(bench jam --scenario "$src/data/scenarios/jam_short_test.yaml" --jammer cw --js 20:60:40
       --mitigation none,excision --onset 25 --out "$work/sweep")
fail=0
check() { if eval "$2"; then echo "ok   $1"; else echo "FAIL $1"; fail=1; fi; }

msg=$("$deepnav" "${sweep[@]}" --modes scalar,ultra 2>&1); rc=$?
check "unknown mode rejected (exit $rc)" '[ $rc -ne 0 ] && grep -q "unknown receiver mode '"'"'ultra'"'"' (available: scalar" <<< "$msg"'
n=$("$deepnav" "${sweep[@]}" --list-commands | grep -c "bench jam-point")
check "4 commands listed ($n)" '[ "$n" -eq 4 ]'
"$deepnav" "${sweep[@]}" --jobs 2 > "$work/first.txt" 2>&1 || { cat "$work/first.txt"; echo "FAIL sweep"; exit 1; }
second=$("$deepnav" "${sweep[@]}" --jobs 2 --no-plots 2>&1)
check "resume: nothing rerun" 'grep -q "4 already finished" <<< "$second" && grep -q "0 to run" <<< "$second"'
n=$("$deepnav" "${sweep[@]}" --list-commands | wc -l)
check "nothing left to list ($n)" '[ "$n" -eq 0 ]'
check "thresholds.md written" '[ -s "$work/sweep/thresholds.md" ] && grep -q "| jam_short_test | cw | scalar | excision |" "$work/sweep/thresholds.md"'
if /usr/bin/python3 -c "import matplotlib" 2> /dev/null; then
  check "plot written" '[ -s "$work/sweep/jam_cw.png" ]'
fi
python3 - "$work/sweep/runs.csv" <<'PY' || fail=1
import csv, sys
rows = {(r["mitigation"], float(r["js_db"])): r for r in csv.DictReader(open(sys.argv[1]))}
def ok(name, cond, value):
    print(("ok   " if cond else "FAIL ") + name, value)
    return cond
good = True
r = rows[("none", 20.0)]
good &= ok("J/S 20 dB, no mitigation: fix kept within 10 m", r["failed"] == "0" and float(r["horizontal_max_m"]) < 10, (r["failed"], r["horizontal_max_m"], r["fix_availability"]))
good &= ok("J/S 20 dB: channels tracked", float(r["tracked_fraction_mean"]) > 0.9, r["tracked_fraction_mean"])
r = rows[("none", 60.0)]
good &= ok("J/S 60 dB, no mitigation: fails", r["failed"] == "1", (r["failure"], r["cn0_mean_dbhz"]))
r = rows[("excision", 60.0)]
good &= ok("J/S 60 dB, excision: fix kept within 10 m", r["failed"] == "0", (r["failure"], r["horizontal_max_m"], r["cn0_mean_dbhz"]))
good &= ok("J/S 60 dB, excision: C/N0 above 35 dB-Hz", float(r["cn0_mean_dbhz"]) > 35, r["cn0_mean_dbhz"])
sys.exit(0 if good and len(rows) == 4 else 1)
PY
[ $fail -eq 0 ] || { cat "$work/first.txt"; exit 1; }
