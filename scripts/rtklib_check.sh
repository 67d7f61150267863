#!/usr/bin/env bash
# Independent check of the receiver's RINEX products: RTKLIB's rnx2rtkp (Debian package
# rtklib) solves single-point positions from our obs.rnx and nav.rnx, and each is compared
# with our own fix of the same epoch (pvt.csv). Passes when all agree within the bound
# (3-D; 5 m unless --bound says otherwise).
#   usage: scripts/rtklib_check.sh RUN_DIR [--sys G|E|G,E] [--nav FILE] [--bound M]
#                                  [--atmosphere none] [--min-satellites N]
#     RUN_DIR: a `deepnav run --out` folder; --sys: the systems RTKLIB takes (rnx2rtkp -sys,
#     default G); --nav: another navigation file than the run's nav.rnx (an assisted run's
#     --ephemeris-from file, whose records the run used); --atmosphere none: RTKLIB applies
#     no ionosphere or troposphere model (for a run with --ionosphere none --troposphere none
#     on IF synthesized without them: the two solvers then weigh only the same noise);
#     --min-satellites: every RTKLIB fix must use at least N satellites (so that both
#     systems' observations were read)
set -euo pipefail
run=${1:?usage: scripts/rtklib_check.sh RUN_DIR [--sys G|E|G,E] [--nav FILE] [--bound M] [--atmosphere none] [--min-satellites N]}
shift
systems=G nav="$run/nav.rnx" bound=5 iono=brdc tropo=saas min_satellites=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --sys) systems=$2; shift 2 ;;
    --nav) nav=$2; shift 2 ;;
    --bound) bound=$2; shift 2 ;;
    --atmosphere)
      [[ $2 == none ]] || { echo "rtklib_check.sh: --atmosphere $2: expected none" >&2; exit 2; }
      iono=off tropo=off; shift 2 ;;
    --min-satellites) min_satellites=$2; shift 2 ;;
    *) echo "rtklib_check.sh: unknown option '$1' (expected --sys, --nav, --bound, --atmosphere or --min-satellites)" >&2
       exit 2 ;;
  esac
done
navsys=0
for system in ${systems//,/ }; do
  case $system in
    G) navsys=$((navsys | 1)) ;;
    E) navsys=$((navsys | 8)) ;;
    *) echo "rtklib_check.sh: --sys $systems: unknown system '$system' (expected G and/or E)" >&2; exit 2 ;;
  esac
done
command -v rnx2rtkp >/dev/null || { echo "rnx2rtkp is not installed: apt-get install rtklib" >&2; exit 2; }
# Single point, broadcast Klobuchar (GPS's, on E1 too) and Saastamoinen (the models deepnav
# applies), ECEF output with GPS time of week.
conf=$(mktemp)
trap 'rm -f "$conf"' EXIT
cat > "$conf" <<CONF
pos1-posmode       =single
pos1-navsys        =$navsys
pos1-ionoopt       =$iono
pos1-tropopt       =$tropo
pos1-elmask        =5
out-solformat      =xyz
out-timesys        =gpst
out-timeform       =tow
CONF
rnx2rtkp -k "$conf" -sys "$systems" -o "$run/rtklib.pos" "$run/obs.rnx" "$nav" 2>/dev/null
python3 - "$run" "$bound" "$min_satellites" <<'PY'
import csv, math, sys
run, bound, min_satellites = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
ours = {}
for r in csv.DictReader(open(f"{run}/pvt.csv")):
    ours[round(float(r["gps_sow"]), 3)] = (float(r["x_ecef_m"]), float(r["y_ecef_m"]), float(r["z_ecef_m"]))
diffs, fewest = [], None
for line in open(f"{run}/rtklib.pos"):
    if line.startswith("%") or not line.strip():
        continue
    f = line.split()
    sow, xyz = round(float(f[1]), 3), tuple(float(v) for v in f[2:5])
    fewest = int(f[6]) if fewest is None else min(fewest, int(f[6]))
    if sow in ours:
        diffs.append(math.dist(xyz, ours[sow]))
if not diffs:
    print("no common epochs between rtklib.pos and pvt.csv", file=sys.stderr)
    sys.exit(2)
rms = math.sqrt(sum(d * d for d in diffs) / len(diffs))
print(f"epochs compared: {len(diffs)}; RTKLIB vs deepnav 3-D difference: rms {rms:.2f} m, max {max(diffs):.2f} m "
      f"(bound {bound:g} m); RTKLIB used at least {fewest} satellites")
sys.exit(0 if max(diffs) <= bound and fewest >= min_satellites else 1)
PY
