#!/usr/bin/env bash
# Cold-start time to first fix against where in the navigation frame a recording starts:
# data/scenarios/ttff_static_40s.yaml (static, 45 dB-Hz, 2.6 Msps ibyte like gps-sdr-sim)
# started 0, 3, 9, 15, 21 and 27 s after a subframe 1 boundary, plus RANDOM offsets in
# [0, 30) s drawn from SEED. Each start is synthesized and run cold (no ephemerides given;
# --week from the synthesis, as for any file whose date is known). Prints a Markdown table:
# when the ephemerides of four satellites were complete, the first fix, and the earliest the
# broadcast data allow (the end of the last word needed, first received whole after the start,
# plus 70 ms of travel); with --json FILE the same as JSON.
# --hot ERROR_S runs each start hot instead: the broadcast ephemerides given
# (--ephemeris-from data/brdc0010.22n) and --time-hint the true start plus ERROR_S, with
# --position-hint LAT,LON,H when given; the table then adds the first fix's horizontal error
# and the RMS of the fixes from 20 s on (the steady state), against the truth; over all the
# starts, the RMS of the first fixes' errors against the steady RMS.
#   usage: scripts/ttff_offsets.sh DEEPNAV OUT [--random N] [--seed S] [--json FILE]
#                                  [--hot ERROR_S [--position-hint LAT,LON,H]]
#   e.g.   scripts/ttff_offsets.sh build/tools/deepnav /tmp/ttff --random 20 --seed 1 --json /tmp/ttff/ttff.json
set -euo pipefail
deepnav=$1
out=$2
shift 2
random=20 seed=1 json="" hot="" position_hint=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --random) random=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --json) json=$2; shift 2 ;;
    --hot) hot=$2; shift 2 ;;
    --position-hint) position_hint=$2; shift 2 ;;
    *) echo "ttff_offsets.sh: unknown option '$1' (expected --random N, --seed S, --json FILE, --hot ERROR_S or" \
         "--position-hint LAT,LON,H)" >&2; exit 2 ;;
  esac
done
src=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
offsets=(0 3 9 15 21 27)
RANDOM=$seed
# printf -v, not $(printf ...): bash seeds RANDOM afresh in a subshell, so offsets drawn in
# one would differ from run to run whatever the seed.
for ((k = 0; k < random; k++)); do
  printf -v drawn '%d.%03d' $((RANDOM % 30)) $((RANDOM % 1000))
  offsets+=("$drawn")
done
for offset in "${offsets[@]}"; do
  point="$out/offset_$offset"
  [ -f "$point/run/summary.json" ] && continue
  mkdir -p "$point"
  start=$(printf '2022-01-01T02:00:%06.3f' "$offset")
  sed "s/^start_time: .*/start_time: \"$start\"/" "$src/data/scenarios/ttff_static_40s.yaml" > "$point/scenario.yaml"
  echo "offset $offset s" >&2
  "$deepnav" -q sim --scenario "$point/scenario.yaml" --out "$point/sim" > /dev/null
  start_options=(--week 2190)
  if [[ -n $hot ]]; then
    hint=$(python3 -c "import datetime as d, sys; t = d.datetime(2022, 1, 1, 2) + d.timedelta(seconds=float(sys.argv[1]) + float(sys.argv[2])); print(t.strftime('%Y-%m-%dT%H:%M:%S.%f')[:-3])" "$offset" "$hot")
    start_options=(--ephemeris-from "$src/data/brdc0010.22n" --time-hint "$hint")
    [[ -n $position_hint ]] && start_options+=(--position-hint "$position_hint")
  fi
  "$deepnav" -q run --input "$point/sim/if_ibyte.bin" --format ibyte --fs 2600000 "${start_options[@]}" \
    --truth "$point/sim/truth.csv" --out "$point/run.tmp" > "$point/run.log"
  rm -rf "$point/run"
  mv "$point/run.tmp" "$point/run"
  # The first fix's horizontal error and the steady state's (fixes from 20 s on), for --hot.
  python3 - "$point/run/pvt.csv" "$point/sim/truth.csv" > "$point/run/errors.json" <<'PY'
import csv, json, math, sys
truth = {round(float(r["t_s"]), 3): r for r in csv.DictReader(open(sys.argv[2]))}
def horizontal(fix):
    t = truth[round(float(fix["t_s"]), 3)]
    lat, lon = math.radians(float(fix["lat_deg"])), math.radians(float(fix["lon_deg"]))
    d = [float(t[a + "_ecef_m"]) - float(fix[a + "_ecef_m"]) for a in "xyz"]
    north = -math.sin(lat) * math.cos(lon) * d[0] - math.sin(lat) * math.sin(lon) * d[1] + math.cos(lat) * d[2]
    east = -math.sin(lon) * d[0] + math.cos(lon) * d[1]
    return math.hypot(north, east)
# Fixes at the scenario's very end have no truth row: not scored.
fixes = [r for r in csv.DictReader(open(sys.argv[1])) if r["valid"] == "1" and round(float(r["t_s"]), 3) in truth]
steady = [horizontal(r) for r in fixes if float(r["t_s"]) >= 20.0]
print(json.dumps({"first_fix_error_m": horizontal(fixes[0]) if fixes else None,
                  "steady_rms_error_m": math.sqrt(sum(e * e for e in steady) / len(steady)) if steady else None,
                  "largest_error_m": max(map(horizontal, fixes)) if fixes else None}))
PY
  rm -rf "$point/sim"
  find "$point/run" -type f ! -name summary.json ! -name errors.json -delete
done
python3 - "$out" "$json" "$hot" "${offsets[@]}" <<'PY'
import json, math, sys
out, json_path, hot, offsets = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
# Words (subframe, 0-based index) the ephemerides need, at their place in the 30 s frame.
needed = [(1, w) for w in range(6, 10)] + [(2, w) for w in range(2, 10)] + [(3, w) for w in range(2, 10)]
def earliest(offset, travel=0.07):
    start = offset - travel  # transmit time, in the frame, of what arrives first
    end = 0.0
    for sf, w in needed:
        begin = (sf - 1) * 6.0 + w * 0.6
        # Received whole with the word before's last two bits (40 ms).
        copy = 0 if begin - 0.04 >= start else math.ceil((start - begin + 0.04) / 30.0)
        end = max(end, begin + 0.6 + 30.0 * copy)
    return end - offset + travel
rows = []
for o in offsets:
    s = json.load(open(f"{out}/offset_{o}/run/summary.json"))
    ff = s.get("first_fix") or {}
    row = {"offset_s": float(o), "ephemerides_complete_s": ff.get("ephemerides_complete_s"),
           "first_fix_s": s["time_to_first_fix_s"], "method": ff.get("method"),
           "earliest_data_s": round(earliest(float(o)), 3)}
    if hot:
        row.update(json.load(open(f"{out}/offset_{o}/run/errors.json")))
        row["time_correction_s"] = (s.get("hot_start") or {}).get("first_time_correction_s")
    rows.append(row)
fixes = [r["first_fix_s"] for r in rows if r["first_fix_s"] is not None]
summary = {"starts": len(rows), "fixed": len(fixes), "mean_first_fix_s": sum(fixes) / len(fixes) if fixes else None,
           "max_first_fix_s": max(fixes) if fixes else None}
fmt = lambda v: "-" if v is None else f"{v:.2f}"
if hot:
    print("| start offset (s) | first fix (s) | method | time correction (s) | first fix error (m) | "
          "steady RMS (m) | largest error (m) |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['offset_s']:.3f} | {fmt(r['first_fix_s'])} | {r['method'] or '-'} | {fmt(r['time_correction_s'])} | "
              f"{fmt(r['first_fix_error_m'])} | {fmt(r['steady_rms_error_m'])} | {fmt(r['largest_error_m'])} |")
    scored = [r for r in rows if r["first_fix_error_m"] is not None and r["steady_rms_error_m"]]
    rms = lambda v: math.sqrt(sum(x * x for x in v) / len(v)) if v else None
    summary["first_fix_error_rms_m"] = rms([r["first_fix_error_m"] for r in scored])
    summary["steady_error_rms_m"] = rms([r["steady_rms_error_m"] for r in scored])
    summary["first_fix_within_twice_steady"] = sum(r["first_fix_error_m"] <= 2 * r["steady_rms_error_m"] for r in scored)
    summary["largest_error_m"] = max((r["largest_error_m"] for r in rows if r["largest_error_m"] is not None), default=None)
else:
    print("| start offset (s) | ephemerides complete (s) | first fix (s) | earliest the data allow (s) | method |")
    print("|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['offset_s']:.3f} | {fmt(r['ephemerides_complete_s'])} | {fmt(r['first_fix_s'])} | "
              f"{r['earliest_data_s']:.2f} | {r['method'] or '-'} |")
print(f"\n{summary['fixed']} of {summary['starts']} starts fixed; first fix mean {fmt(summary['mean_first_fix_s'])} s, "
      f"max {fmt(summary['max_first_fix_s'])} s")
if hot:
    print(f"first fixes' horizontal RMS {fmt(summary['first_fix_error_rms_m'])} m against the steady state's "
          f"{fmt(summary['steady_error_rms_m'])} m; {summary['first_fix_within_twice_steady']} of {len(rows)} first "
          f"fixes within twice their run's steady RMS; largest error of any fix {fmt(summary['largest_error_m'])} m")
if json_path:
    with open(json_path, "w") as f:
        json.dump({"starts": rows, "summary": summary}, f, indent=2)
PY
