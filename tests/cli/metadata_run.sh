#!/usr/bin/env bash
# ION GNSS SDR metadata files configure the source with no other flags: the real captures in
# data/ are acquired from their .xml alone (same PRNs as with the flags), the receiver runs
# on one; `deepnav sim` writes an .xml beside its IF file for every whole-byte format
# (ibyte, ishort, gr_complex, byte) and `deepnav run --metadata` alone fixes from each
# (cli.format_cu8 and cli.format_packed do the same for cu8 and the packed layouts). Broken
# or unsupported metadata exits non-zero naming the file and the element.
#   usage: metadata_run.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$(realpath "$1")
src=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

# The real captures.
"$deepnav" -q acquire --metadata "$src/data/L1_20211202_084700_4MHz_IQ.xml" --json "$work/iq.json" > /dev/null \
  || fail "acquire --metadata L1_20211202_084700_4MHz_IQ.xml"
"$deepnav" -q acquire --metadata "$src/data/L1_20211125_004000_12MHz_I.xml" --json "$work/i.json" > /dev/null \
  || fail "acquire --metadata L1_20211125_004000_12MHz_I.xml"
python3 - "$work/iq.json" "$work/i.json" <<'PY' || failures=$((failures + 1))
import json, sys
expected = [
    {31: (-190, 1159), 26: (650, 3599), 29: (-2220, 1653), 16: (2600, 3958), 32: (-3380, 2766)},
    {5: (140, 5611), 13: (-230, 6004), 20: (-1370, 8172), 15: (1730, 9317), 2: (-2740, 5328), 30: (-1880, 4719),
     11: (-3280, 11004), 18: (3280, 6580), 29: (-2030, 9075)},
]
bad = 0
for path, exp in zip(sys.argv[1:], expected):
    doc = json.load(open(path))
    found = {r["prn"]: r for r in doc["results"] if r["detected"]}
    missing = [p for p, (dop, delay) in exp.items()
               if p not in found or abs(found[p]["doppler_hz"] - dop) > 250 or abs(found[p]["delay_samples"] - delay) > 2]
    ok = not missing
    print(("ok  " if ok else "FAIL"), path.split("/")[-1], "from metadata alone:", doc["sample_rate_hz"], "Hz, IF",
          doc["if_hz"], "Hz; PRNs", sorted(found), "missing" if missing else "", missing or "")
    bad += not ok
sys.exit(1 if bad else 0)
PY
"$deepnav" -q run --metadata "$src/data/L1_20211202_084700_4MHz_IQ.xml" --out "$work/real" > /dev/null \
  || fail "run --metadata on the real capture"
python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); assert len(s["acquired_prns"]) >= 5, s["acquired_prns"]; print("ok   run --metadata on the 4 MHz capture: acquired", s["acquired_prns"])' \
  "$work/real/summary.json" || fail "run on the real capture acquired too little"

# Whole-byte formats synthesized and fixed from the metadata the synthesizer wrote.
for layout in "ibyte 2048000 0 4" "ishort 2048000 0 12" "gr_complex 2048000 0 0" "byte 5000000 1250000 4"; do
  read -r format fs if_hz bits <<< "$layout"
  sed -e 's/duration_s: 120/duration_s: 22/' -e "s/sample_rate_hz: 2600000/sample_rate_hz: $fs\nif_hz: $if_hz/" \
      -e "s/format: ibyte/format: $format/" -e "s/adc: {bits: 4, agc: true}/adc: {bits: $bits, agc: true}/" \
      "$src/data/scenarios/static_120s.yaml" > "$work/$format.yaml"
  "$deepnav" -q sim --scenario "$work/$format.yaml" --out "$work/$format" > /dev/null || { fail "$format: sim"; continue; }
  xml="$work/$format/if_$format.xml"
  [[ -s $xml ]] || { fail "$format: sim wrote no $(basename "$xml")"; continue; }
  # From another folder: the metadata names its file relative to itself.
  (cd "$work" && "$deepnav" -q run --metadata "$xml" --week 2190 --iono-from "$src/data/brdc0010.22n" \
      --ephemeris-from "$src/data/brdc0010.22n" --truth "$work/$format/truth.csv" --out "$work/$format/run" > /dev/null) \
    || { fail "$format: run --metadata"; continue; }
  python3 - "$work/$format/run/summary.json" "$format" <<'PY' || failures=$((failures + 1))
import json, sys
s = json.load(open(sys.argv[1]))
h = s["horizontal_error_m"]["rms"] if s["fixes"] else float("nan")
ok = s["fixes"] >= 4 and h <= 6.0
print(("ok  " if ok else "FAIL"), f"{sys.argv[2]:10s} run --metadata alone: fixes {s['fixes']}, horizontal RMS {h:.2f} m")
sys.exit(0 if ok else 1)
PY
  rm -f "$work/$format"/if_*.bin
done

# Bad metadata: non-zero exit, the file and the element named.
expect_error() {  # expect_error TEXT... -- COMMAND...
  local texts=() msg rc t
  while [[ $1 != -- ]]; do texts+=("$1"); shift; done
  shift
  msg=$("$@" 2>&1)
  rc=$?
  for t in "${texts[@]}"; do
    if [[ $rc -eq 0 || $msg != *"$t"* ]]; then fail "$*: exit $rc, message: $msg"; return; fi
  done
  echo "ok   exit $rc: $(head -1 <<< "$msg")"
}
good=$src/data/L1_20211202_084700_4MHz_IQ.xml
sed 's#</lane>#<lane#' "$good" > "$work/broken.xml"
expect_error "broken.xml" "not well-formed XML" -- "$deepnav" -q acquire --metadata "$work/broken.xml"
sed 's#<encoding>INT8</encoding>#<encoding>OG</encoding>#' "$good" > "$work/og.xml"
expect_error "og.xml" "stream[L1]/encoding>" "'OG'" -- "$deepnav" -q run --metadata "$work/og.xml" --out "$work/bad"
sed 's#<lump>#<lump><stream id="L2"/>#' "$good" > "$work/two.xml"
expect_error "two.xml" "lump/stream[L1]>" "2 <stream> elements" -- "$deepnav" -q acquire --metadata "$work/two.xml"
sed 's#<url>L1_20211202_084700_4MHz_IQ.bin</url>#<url>missing.bin</url>#' "$good" > "$work/missing.xml"
expect_error "missing.xml" "missing.bin" "does not exist" -- "$deepnav" -q acquire --metadata "$work/missing.xml"
expect_error "--metadata describes files" -- "$deepnav" -q run --input tcp://127.0.0.1:9 --metadata "$good" --out "$work/bad"
exit $((failures > 0))
