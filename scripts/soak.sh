#!/usr/bin/env bash
# Long-run soak of the IF stream on loopback, as a benchmark with pass/fail criteria:
#  (a) TCP at real time: scripts/stream_memory.sh (PACE=1) runs a short and a long stream;
#      every sample must arrive (0 lost) and the long run's peak RSS must stay within
#      10 % of the short run's.
#  (b) UDP at real time through tests/cli/pylib/peers/udp_impair.py, which drops, duplicates and
#      reorders a seeded fraction of the frame datagrams; the receiver's summary.json must
#      report exactly what was injected (lost frames and samples, duplicates, reordered).
# A table goes to stdout (and with --json FILE the same figures as JSON), progress to
# stderr. Exit status 0 when every criterion holds, 1 when one does not.
#   usage: scripts/soak.sh [--short S] [--long S] [--udp S] [--seed N] [--loss P] [--dup P]
#                        [--reorder P] [--json FILE]
#   defaults: --short 60 --long 3600 --udp 60 --seed 1 --loss 0.001 --dup 0.001 --reorder 0.001
#   --long 0 or --udp 0 skips that part. DEEPNAV=path overrides the binary; SCENARIO=path the
#   scenario (default data/scenarios/static_120s.yaml, synthesized for any duration).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
deepnav=${DEEPNAV:-$root/build/tools/deepnav}
scenario=${SCENARIO:-$root/data/scenarios/static_120s.yaml}
relay_py=$root/tests/cli/pylib/peers/udp_impair.py
short_s=60 long_s=3600 udp_s=60 seed=1 loss=0.001 dup=0.001 reorder=0.001 json=
RSS_RATIO_LIMIT=1.10  # issue 20: the long run's peak RSS within 10 % of the 60 s run's

die() { echo "soak.sh: $*" >&2; exit 2; }
number() { [[ $2 =~ ^[0-9]+([.][0-9]+)?$ ]] || die "$1 '$2' is not a non-negative number"; echo "$2"; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --short) short_s=$(number "$1" "${2:-}"); shift 2 ;;
    --long) long_s=$(number "$1" "${2:-}"); shift 2 ;;
    --udp) udp_s=$(number "$1" "${2:-}"); shift 2 ;;
    --seed) seed=$(number "$1" "${2:-}"); shift 2 ;;
    --loss) loss=$(number "$1" "${2:-}"); shift 2 ;;
    --dup) dup=$(number "$1" "${2:-}"); shift 2 ;;
    --reorder) reorder=$(number "$1" "${2:-}"); shift 2 ;;
    --json) json=${2:?--json needs a file}; shift 2 ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown option '$1' (see --help)" ;;
  esac
done
[[ -x $deepnav ]] || die "no deepnav binary at $deepnav (build first)"

work=$(mktemp -d)
server= relay=
cleanup() {
  [[ -n $relay ]] && kill "$relay" 2>/dev/null
  [[ -n $server ]] && kill "$server" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

# (a) The TCP runs, one after the other, by stream_memory.sh; its own table is progress here.
tcp_soak() {
  echo "soak.sh: TCP at real time, ${short_s} s and ${long_s} s (stream_memory.sh) ..." >&2
  PACE=1 DEEPNAV=$deepnav SCENARIO=$scenario "$root/scripts/stream_memory.sh" --json "$work/tcp.json" \
    "$short_s" "$long_s" >&2
}

port_from() {  # port_from FILE WHAT: the "udp N" line a server or the relay writes once listening
  for _ in $(seq 300); do [[ -s $1 ]] && break; sleep 0.1; done
  local port
  port=$(awk '$1 == "udp" {print $2}' "$1" 2>/dev/null)
  [[ -n $port ]] || die "$2 did not report its UDP port in $1"
  echo "$port"
}

# (b) serve --udp -> udp_impair.py relay -> run --input udp://, then compare what the relay
# did with what the receiver reported.
udp_soak() {
  echo "soak.sh: UDP at real time, ${udp_s} s through udp_impair.py (seed $seed) ..." >&2
  "$deepnav" -q serve --scenario "$scenario" --duration "$udp_s" --udp 0 --pace 1 --sessions 1 \
    --port-file "$work/server_port" &
  server=$!
  local server_port relay_port
  server_port=$(port_from "$work/server_port" "deepnav serve")
  python3 "$relay_py" relay --server "127.0.0.1:$server_port" --port-file "$work/relay_port" \
    --report "$work/relay.json" --seed "$seed" --drop-fraction "$loss" --duplicate-fraction "$dup" \
    --reorder-fraction "$reorder" --idle-timeout 60 &
  relay=$!
  relay_port=$(port_from "$work/relay_port" "udp_impair.py")
  "$deepnav" -q run --input "udp://127.0.0.1:$relay_port" --week 2190 --iono-from "$root/data/brdc0010.22n" \
    --out "$work/udp_run" > /dev/null 2> "$work/udp_run.log" || die "deepnav run on the relayed UDP stream failed: $(tail -3 "$work/udp_run.log")"
  wait "$server" || die "deepnav serve (UDP) exited with an error"
  server=
  wait "$relay" || die "udp_impair.py exited with an error"
  relay=
  # compare's exit status says whether it matched; report() below reads that from its JSON.
  python3 "$relay_py" compare --report "$work/relay.json" --summary "$work/udp_run/summary.json" \
    --json "$work/udp_compare.json" >&2 || true
}

[[ $udp_s == 0 ]] || udp_soak
[[ $long_s == 0 ]] || tcp_soak

# The table and the JSON, from whichever parts ran.
python3 - "$work" "$json" "$RSS_RATIO_LIMIT" "$udp_s" "$seed" "$loss" "$dup" "$reorder" <<'PY'
import json, os, sys
work, json_out, ratio_limit = sys.argv[1], sys.argv[2], float(sys.argv[3])
udp_s, seed, loss, dup, reorder = (float(a) for a in sys.argv[4:9])
result = {}


def load(name):
    path = os.path.join(work, name)
    return json.load(open(path)) if os.path.exists(path) else None


tcp = load("tcp.json")
if tcp:
    rows = tcp["rows"]
    ratio = rows[-1]["peak_rss_mib"] / rows[0]["peak_rss_mib"]
    lost = sum(r["lost_samples"] for r in rows)
    result["tcp"] = {"pace": tcp["pace"], "rows": rows, "peak_rss_ratio": ratio, "peak_rss_ratio_limit": ratio_limit,
                     "lost_samples": lost, "pass": lost == 0 and ratio <= ratio_limit}
    print(f"TCP at real time (deepnav serve --pace 1 -> deepnav run, every product written)")
    print(f"{'duration_s':>12} {'signal_s':>10} {'fixes':>8} {'lost_samples':>13} {'peak_rss_mib':>13} {'cpu_s':>8}")
    for r in rows:
        print(f"{r['duration_s']:>12.0f} {r['signal_s']:>10.1f} {r['fixes']:>8} {r['lost_samples']:>13} "
              f"{r['peak_rss_mib']:>13.1f} {r['cpu_s']:>8.1f}")
    print(f"peak RSS {rows[-1]['duration_s']:.0f} s / {rows[0]['duration_s']:.0f} s: {ratio:.3f} (limit {ratio_limit:.2f}); "
          f"lost samples {lost}: {'pass' if result['tcp']['pass'] else 'FAIL'}")

udp = load("udp_compare.json")
if udp:
    relay = load("relay.json")
    summary = json.load(open(os.path.join(work, "udp_run", "summary.json")))
    rows = {r["field"]: r for r in udp["rows"]}
    shown = [("dropped frames", "frames_lost"), ("missing samples", "lost_samples"),
             ("duplicated frames", "frames_duplicated"), ("reordered frames", "frames_reordered"),
             ("late frames", "frames_late"), ("lost frame ranges", "lost_frame_ranges"), ("gaps", "gaps")]
    result["udp"] = {"duration_s": udp_s, "seed": int(seed), "drop_fraction": loss, "duplicate_fraction": dup,
                     "reorder_fraction": reorder, "frames_from_server": relay["frames_from_server"],
                     "injected": {key: rows[key]["expected"] for _, key in shown},
                     "reported": {key: rows[key]["reported"] for _, key in shown},
                     "fields": udp["rows"], "match": udp["match"],
                     "frames_overrun": summary["stream"]["frames_overrun"],
                     "kernel_udp_rcvbuf_errors": relay["kernel_udp_rcvbuf_errors"],
                     "peak_rss_mib": summary["resources"]["peak_rss_mib"], "pass": udp["match"]}
    if tcp:
        print()
    print(f"UDP at real time through udp_impair.py ({udp_s:.0f} s, {relay['frames_from_server']} frames, seed {seed:.0f}; "
          f"drop {loss}, duplicate {dup}, reorder {reorder} of the frames)")
    print(f"{'':20} {'injected':>10} {'reported':>10}")
    for label, key in shown:
        want, got = rows[key]["expected"], rows[key]["reported"]
        count = (lambda v: len(v) if isinstance(v, list) else v)
        print(f"{label:20} {count(want):>10} {count(got):>10}{'' if rows[key]['equal'] else '   differs'}")
    others = [r["field"] for r in udp["rows"] if not r["equal"] and r["field"] not in dict(shown).values()]
    print(f"exact match of every field: {'yes' if udp['match'] else 'NO'}"
          + (f" (also differs: {', '.join(others)})" if others else "")
          + f"; overruns {result['udp']['frames_overrun']}, kernel UDP receive-buffer drops "
          f"{result['udp']['kernel_udp_rcvbuf_errors']}: {'pass' if udp['match'] else 'FAIL'}")

if json_out:
    os.makedirs(os.path.dirname(os.path.abspath(json_out)), exist_ok=True)
    with open(json_out, "w") as f:
        json.dump(result, f, indent=2)
        f.write("\n")
sys.exit(0 if all(part["pass"] for part in result.values()) else 1)
PY
