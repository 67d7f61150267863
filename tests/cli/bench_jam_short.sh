#!/usr/bin/env bash
# A short jamming sweep (20 s scenario at 2.6 Msps, CW from 14 s at J/S 20 and 60 dB,
# with and without excision, two jobs): the unmitigated receiver keeps its fix at 20 dB
# and loses it at 60 dB, excision keeps it at 60 dB; a second run finds every point
# finished; --list-commands prints one command per unfinished point; an unknown receiver
# mode is rejected naming the available ones, an aided mode on a scenario without an IMU
# is rejected; one ultra-tight point (CW at 20 dB) passes with its solution from the
# ultra-tight filter for the whole jammed window.
#   usage: bench_jam_short.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sweep=(bench jam --scenario "$src/data/scenarios/jam_short_test.yaml" --jammer cw --js 20:60:40
       --mitigation none,excision --onset 14 --out "$work/sweep")
fail=0
check() { if eval "$2"; then echo "ok   $1"; else echo "FAIL $1"; fail=1; fi; }

msg=$("$deepnav" "${sweep[@]}" --modes scalar,vector 2>&1); rc=$?
check "unknown mode rejected (exit $rc)" '[ $rc -ne 0 ] && grep -q "unknown receiver mode '"'"'vector'"'"' (available: scalar, loose, tight, ultra)" <<< "$msg"'
msg=$("$deepnav" bench jam --scenario "$src/data/scenarios/static_120s.yaml" --jammer cw --js 20 --modes tight \
      --out "$work/noimu" --list-commands 2>&1); rc=$?
check "aided mode without an IMU rejected (exit $rc)" '[ $rc -ne 0 ] && grep -q "needs an IMU" <<< "$msg"'
n=$("$deepnav" "${sweep[@]}" --list-commands | grep -c "bench jam-point")
check "4 commands listed ($n)" '[ "$n" -eq 4 ]'
"$deepnav" "${sweep[@]}" --jobs 2 --no-plots > "$work/first.txt" 2>&1 || { cat "$work/first.txt"; echo "FAIL sweep"; exit 1; }
second=$("$deepnav" "${sweep[@]}" --jobs 2 --no-plots 2>&1)
check "resume: nothing rerun" 'grep -q "4 already finished" <<< "$second" && grep -q "0 to run" <<< "$second"'
n=$("$deepnav" "${sweep[@]}" --list-commands | wc -l)
check "nothing left to list ($n)" '[ "$n" -eq 0 ]'
# One ultra-tight point into the same folder; the report then covers all five.
"$deepnav" bench jam --scenario "$src/data/scenarios/jam_short_test.yaml" --jammer cw --js 20 --modes ultra \
  --mitigation none --onset 14 --out "$work/sweep" > "$work/ultra.txt" 2>&1 || { cat "$work/ultra.txt"; echo "FAIL ultra sweep"; exit 1; }
check "thresholds.md written" '[ -s "$work/sweep/thresholds.md" ] && grep -q "| jam_short_test | cw | scalar | excision |" "$work/sweep/thresholds.md" && grep -q "| jam_short_test | cw | ultra | none |" "$work/sweep/thresholds.md"'
if /usr/bin/python3 -c "import matplotlib" 2> /dev/null; then
  check "plot written" '[ -s "$work/sweep/jam_cw.png" ]'
fi
python3 - "$work/sweep" <<'PY' || fail=1
import csv, glob, json, sys
folder = sys.argv[1]
rows = {(r["mode"], r["mitigation"], float(r["js_db"])): r for r in csv.DictReader(open(f"{folder}/runs.csv"))}
def ok(name, cond, value):
    print(("ok   " if cond else "FAIL ") + name, value)
    return cond
good = True
r = rows[("scalar", "none", 20.0)]
good &= ok("J/S 20 dB, no mitigation: fix kept within 10 m", r["failed"] == "0" and float(r["horizontal_max_m"]) < 10, (r["failed"], r["horizontal_max_m"], r["fix_availability"]))
good &= ok("J/S 20 dB: channels tracked", float(r["tracked_fraction_mean"]) > 0.9, r["tracked_fraction_mean"])
r = rows[("scalar", "none", 60.0)]
good &= ok("J/S 60 dB, no mitigation: fails", r["failed"] == "1", (r["failure"], r["cn0_mean_dbhz"]))
r = rows[("scalar", "excision", 60.0)]
good &= ok("J/S 60 dB, excision: fix kept within 10 m", r["failed"] == "0", (r["failure"], r["horizontal_max_m"], r["cn0_mean_dbhz"]))
good &= ok("J/S 60 dB, excision: C/N0 above 35 dB-Hz", float(r["cn0_mean_dbhz"]) > 35, r["cn0_mean_dbhz"])
r = rows[("ultra", "none", 20.0)]
good &= ok("ultra, J/S 20 dB: passes with every epoch a GNSS fix", r["failed"] == "0" and float(r["fix_availability"]) == 1.0, (r["failure"], r["fix_availability"], r["horizontal_max_m"]))
good &= ok("ultra, J/S 20 dB: the solution is the ultra-tight filter's throughout", r["epochs_in_mode"].split() == ["ultra:6"], r["epochs_in_mode"])
p = json.load(open(glob.glob(f"{folder}/points/*_ultra_none_s1/point.json")[0]))
changes = [(c["from"], c["to"]) for c in p["mode_changes"]]
good &= ok("ultra point: one mode change scalar -> ultra before the onset", changes == [("scalar", "ultra")] and p["mode_changes"][0]["t_s"] < 14, p["mode_changes"])
good &= ok("ultra point: run with the IMU and assisted ephemerides", all(a in p["command"] for a in ("--mode ultra", "--imu ", "--imu-grade tactical", "--imu-lever-arm 0.5 0 -0.3", "--ephemeris-from")), p["command"])
sys.exit(0 if good and len(rows) == 5 else 1)
PY
[ $fail -eq 0 ] || { cat "$work/first.txt"; exit 1; }
