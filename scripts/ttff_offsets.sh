#!/usr/bin/env bash
# Cold-start time to first fix against where in the navigation frame a recording starts:
# data/scenarios/ttff_static_40s.yaml (static, 45 dB-Hz, 2.6 Msps ibyte like gps-sdr-sim)
# started 0, 3, 9, 15, 21 and 27 s after a subframe 1 boundary, plus RANDOM offsets in
# [0, 30) s drawn from SEED. Each start is synthesized and run cold (no ephemerides given;
# --week from the synthesis, as for any file whose date is known). Prints a Markdown table:
# when the ephemerides of four satellites were complete, the first fix, and the earliest the
# broadcast data allow (the end of the last word needed, first received whole after the start,
# plus 70 ms of travel); with --json FILE the same as JSON.
#   usage: scripts/ttff_offsets.sh DEEPNAV OUT [--random N] [--seed S] [--json FILE]
#   e.g.   scripts/ttff_offsets.sh build/tools/deepnav /tmp/ttff --random 20 --seed 1 --json /tmp/ttff/ttff.json
set -euo pipefail
deepnav=$1
out=$2
shift 2
random=20 seed=1 json=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --random) random=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --json) json=$2; shift 2 ;;
    *) echo "ttff_offsets.sh: unknown option '$1' (expected --random N, --seed S or --json FILE)" >&2; exit 2 ;;
  esac
done
src=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
offsets=(0 3 9 15 21 27)
RANDOM=$seed
for ((k = 0; k < random; k++)); do offsets+=("$(printf '%d.%03d' $((RANDOM % 30)) $((RANDOM % 1000)))"); done
for offset in "${offsets[@]}"; do
  point="$out/offset_$offset"
  [ -f "$point/run/summary.json" ] && continue
  mkdir -p "$point"
  start=$(printf '2022-01-01T02:00:%06.3f' "$offset")
  sed "s/^start_time: .*/start_time: \"$start\"/" "$src/data/scenarios/ttff_static_40s.yaml" > "$point/scenario.yaml"
  echo "offset $offset s" >&2
  "$deepnav" -q sim --scenario "$point/scenario.yaml" --out "$point/sim" > /dev/null
  "$deepnav" -q run --input "$point/sim/if_ibyte.bin" --format ibyte --fs 2600000 --week 2190 \
    --out "$point/run.tmp" > "$point/run.log"
  rm -rf "$point/sim" "$point/run"
  mv "$point/run.tmp" "$point/run"
  find "$point/run" -type f ! -name summary.json -delete
done
python3 - "$out" "$json" "${offsets[@]}" <<'PY'
import json, math, sys
out, json_path, offsets = sys.argv[1], sys.argv[2], sys.argv[3:]
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
    rows.append({"offset_s": float(o), "ephemerides_complete_s": ff.get("ephemerides_complete_s"),
                 "first_fix_s": s["time_to_first_fix_s"], "method": ff.get("method"),
                 "earliest_data_s": round(earliest(float(o)), 3)})
fixes = [r["first_fix_s"] for r in rows if r["first_fix_s"] is not None]
summary = {"starts": len(rows), "fixed": len(fixes), "mean_first_fix_s": sum(fixes) / len(fixes) if fixes else None,
           "max_first_fix_s": max(fixes) if fixes else None}
print("| start offset (s) | ephemerides complete (s) | first fix (s) | earliest the data allow (s) | method |")
print("|---|---|---|---|---|")
fmt = lambda v: "-" if v is None else f"{v:.2f}"
for r in rows:
    print(f"| {r['offset_s']:.3f} | {fmt(r['ephemerides_complete_s'])} | {fmt(r['first_fix_s'])} | "
          f"{r['earliest_data_s']:.2f} | {r['method'] or '-'} |")
print(f"\n{summary['fixed']} of {summary['starts']} starts fixed; first fix mean {fmt(summary['mean_first_fix_s'])} s, "
      f"max {fmt(summary['max_first_fix_s'])} s")
if json_path:
    with open(json_path, "w") as f:
        json.dump({"starts": rows, "summary": summary}, f, indent=2)
PY
