#!/usr/bin/env bash
# Peak memory of `deepnav run` on a TCP stream against the stream's length: for each
# duration, `deepnav serve` synthesizes a static scenario on the fly (as fast as the
# client reads) and `deepnav run --input tcp://...` writes every product; the peak
# resident memory comes from the run's summary.json (`resources.peak_rss_mib`). Products
# are written as the run goes, so the peak must not grow with the run's length.
#   usage: scripts/stream_memory.sh [--json FILE] [DURATION_S ...]   (default: 60 600)
#   DEEPNAV=path overrides the binary; SCENARIO=path the scenario (default static_120s.yaml);
#   PACE=multiple of real time the server keeps (default 1: a live stream; 0: as fast as the
#   receiver reads, where the receive queue, up to 64 MiB, fills when the server outruns it).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
deepnav=${DEEPNAV:-$root/build/tools/deepnav}
scenario=${SCENARIO:-$root/data/scenarios/static_120s.yaml}
pace=${PACE:-1}
json=
durations=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --json) json=${2:?--json needs a file}; shift 2 ;;
    *) [[ $1 =~ ^[0-9]+([.][0-9]+)?$ ]] || { echo "stream_memory.sh: '$1' is not a duration in seconds" >&2; exit 2; }
       durations+=("$1"); shift ;;
  esac
done
[[ ${#durations[@]} -gt 0 ]] || durations=(60 600)
[[ -x $deepnav ]] || { echo "stream_memory.sh: no deepnav binary at $deepnav (build first)" >&2; exit 2; }
work=$(mktemp -d)
server=
trap '[[ -n $server ]] && kill $server 2>/dev/null; rm -rf "$work"' EXIT
rows=()
for d in "${durations[@]}"; do
  rm -f "$work/ports"
  "$deepnav" -q serve --scenario "$scenario" --duration "$d" --tcp 0 --pace "$pace" --sessions 1 --port-file "$work/ports" &
  server=$!
  for _ in $(seq 300); do [[ -s $work/ports ]] && break; sleep 0.1; done
  port=$(awk '$1 == "tcp" {print $2}' "$work/ports")
  [[ -n $port ]] || { echo "stream_memory.sh: serve did not report its port" >&2; exit 1; }
  echo "stream_memory.sh: $d s over tcp://127.0.0.1:$port ..." >&2
  "$deepnav" -q run --input "tcp://127.0.0.1:$port" --week 2190 --iono-from "$root/data/brdc0010.22n" \
    --out "$work/run_$d" > /dev/null
  wait $server
  server=
  rows+=("$(python3 - "$work/run_$d" "$d" <<'PY'
import json, os, sys
out, d = sys.argv[1], float(sys.argv[2])
s = json.load(open(os.path.join(out, "summary.json")))
size = sum(os.path.getsize(os.path.join(out, f)) for f in os.listdir(out))
print(json.dumps({"duration_s": d, "signal_s": s["duration_s"], "fixes": s["fixes"],
                  "peak_rss_mib": s["resources"]["peak_rss_mib"], "cpu_s": s["resources"]["cpu_s"],
                  "lost_samples": s["stream"]["lost_samples"], "products_mib": size / 2**20}))
PY
)")
  rm -rf "$work/run_$d"
done
printf '%s\n' "${rows[@]}" > "$work/rows.jsonl"
python3 - "$work/rows.jsonl" "$json" "$pace" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
cols = ["duration_s", "fixes", "peak_rss_mib", "cpu_s", "lost_samples", "products_mib"]
print(f"Peak memory of a streamed run (deepnav run on tcp://, every product written; server pace {sys.argv[3]})")
print(" ".join(f"{c:>13}" for c in cols))
for r in rows:
    print(" ".join(f"{r[c]:>13.1f}" if isinstance(r[c], float) else f"{r[c]:>13}" for c in cols))
if len(rows) > 1:
    print(f"peak RSS, longest run / shortest run: {rows[-1]['peak_rss_mib'] / rows[0]['peak_rss_mib']:.3f}")
if sys.argv[2]:
    with open(sys.argv[2], "w") as f:
        json.dump({"pace": float(sys.argv[3]), "rows": rows}, f, indent=2)
PY
