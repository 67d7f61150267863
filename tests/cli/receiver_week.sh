#!/usr/bin/env bash
# The GPS week of every product comes from the signal: the 2022-01-01 data run without
# --week (and without assistance) once came out dated the day of the run in pvt.csv, obs.rnx,
# NMEA and GPX while nav.rnx said 2022. The satellites broadcast the week modulo 1024; the
# build date resolves it, and every product must say 2022-01-01 (week 2190). A --week that
# contradicts the signal is an error naming it; a --week a week off (data across a week
# boundary) is not.
#   usage: receiver_week.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL $*"; exit 1; }
# The bundled scenario from 3 s before a subframe 1 (sow 532800 is a multiple of 30 s) for
# 27 s: subframes 1-3, a whole ephemeris, are in by about 22 s.
sed -e 's/start_time: "2022-01-01T02:00:00"/start_time: "2022-01-01T01:59:57"/' -e 's/duration_s: 60/duration_s: 27/' \
  -e "s#nav_file: data/brdc0010.22n#nav_file: $src/data/brdc0010.22n#" "$src/data/scenarios/default.yaml" > "$work/week.yaml"
"$deepnav" -q sim --scenario "$work/week.yaml" --out "$work/sim" > /dev/null || fail "sim"
run() { "$deepnav" -q run --input "$work/sim/if_ibyte.bin" --fs 4092000 "$@"; }

"$deepnav" run --input "$work/sim/if_ibyte.bin" --fs 4092000 --out "$work/noweek" > "$work/noweek.txt" 2> "$work/noweek.err" || fail "run without --week: $(cat "$work/noweek.err")"
python3 - "$work/noweek" <<'PY' || exit 1
import csv, sys
d = sys.argv[1]
bad = []
rows = list(csv.DictReader(open(f"{d}/pvt.csv")))
if not rows:
    bad.append("pvt.csv has no fix")
weeks = {r["gps_week"] for r in rows}
if weeks - {"2190"}:
    bad.append(f"pvt.csv weeks {weeks}")
obs = open(f"{d}/obs.rnx").read()
first = [l for l in obs.splitlines() if "TIME OF FIRST OBS" in l]
if not first or first[0].split()[:3] != ["2022", "1", "1"]:
    bad.append(f"obs.rnx {first}")
epochs = [l for l in obs.splitlines() if l.startswith(">")]
if not epochs or any(not e.startswith("> 2022 01 01") for e in epochs):
    bad.append(f"obs.rnx epochs {epochs[:1]}")
nmea = [l for l in open(f"{d}/fixes.nmea") if l.startswith("$GPRMC") or l.startswith("$GNRMC")]
if not nmea or any(l.split(",")[9] != "010122" for l in nmea):
    bad.append(f"NMEA dates {[l.split(',')[9] for l in nmea[:2]]}")
gpx = open(f"{d}/track.gpx").read()
if "<time>2022-01-01T" not in gpx or gpx.count("<time>") != gpx.count("<time>2022-01-01T"):
    bad.append("GPX times not all 2022-01-01")
nav = open(f"{d}/nav.rnx").read()
records = [l for l in nav.splitlines() if l.startswith("G")]
if not records or any(" 2022 01 01 " not in l for l in records):
    bad.append(f"nav.rnx records {records[:1]}")
print("\n".join("FAIL " + b for b in bad) if bad else f"ok   no --week: {len(rows)} fixes, every product dated 2022-01-01 (week 2190)")
sys.exit(1 if bad else 0)
PY
grep -q "GPS week 2190" "$work/noweek.err" || fail "no log line naming the week: $(cat "$work/noweek.err")"

# --week one off is a hint the signal settles; more is a contradiction, reported at once.
run --week 2191 --out "$work/week2191" > /dev/null 2>&1 || fail "--week 2191 (one week off) was refused"
out=$(run --week 2195 --out "$work/week2195" 2>&1 >/dev/null)
rc=$?
[[ $rc -ne 0 ]] || fail "--week 2195 accepted"
[[ $out == *"--week 2195 contradicts the signal"*"week number 142 (modulo 1024), i.e. week 2190"*"give --week 2190"* ]] ||
  fail "--week 2195 message: $out"
echo "ok   --week 2195: $out"
cmp -s <(cut -d, -f2- "$work/noweek/pvt.csv") <(cut -d, -f2- "$work/week2191/pvt.csv") ||
  fail "pvt.csv with --week 2191 differs from the run without"
echo "ok   --week 2191 gives the same pvt.csv"
