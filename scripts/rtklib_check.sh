#!/usr/bin/env bash
# Independent check of the receiver's RINEX products: RTKLIB's rnx2rtkp (Debian package
# rtklib) solves single-point positions from our obs.rnx and nav.rnx, and each is compared
# with our own fix of the same epoch (pvt.csv). Passes when all agree within 5 m (3-D).
#   usage: scripts/rtklib_check.sh RUN_DIR        (RUN_DIR: a `deepnav run --out` folder)
set -euo pipefail
run=${1:?usage: scripts/rtklib_check.sh RUN_DIR}
command -v rnx2rtkp >/dev/null || { echo "rnx2rtkp is not installed: apt-get install rtklib" >&2; exit 2; }
# Single point, GPS, broadcast Klobuchar and Saastamoinen (the models deepnav applies),
# ECEF output with GPS time of week.
conf=$(mktemp)
trap 'rm -f "$conf"' EXIT
cat > "$conf" <<'CONF'
pos1-posmode       =single
pos1-navsys        =1
pos1-ionoopt       =brdc
pos1-tropopt       =saas
pos1-elmask        =5
out-solformat      =xyz
out-timesys        =gpst
out-timeform       =tow
CONF
rnx2rtkp -k "$conf" -o "$run/rtklib.pos" "$run/obs.rnx" "$run/nav.rnx" 2>/dev/null
python3 - "$run" <<'PY'
import csv, math, sys
run = sys.argv[1]
ours = {}
for r in csv.DictReader(open(f"{run}/pvt.csv")):
    ours[round(float(r["gps_sow"]), 3)] = (float(r["x_ecef_m"]), float(r["y_ecef_m"]), float(r["z_ecef_m"]))
diffs = []
for line in open(f"{run}/rtklib.pos"):
    if line.startswith("%") or not line.strip():
        continue
    f = line.split()
    sow, xyz = round(float(f[1]), 3), tuple(float(v) for v in f[2:5])
    if sow in ours:
        diffs.append(math.dist(xyz, ours[sow]))
if not diffs:
    print("no common epochs between rtklib.pos and pvt.csv", file=sys.stderr)
    sys.exit(2)
rms = math.sqrt(sum(d * d for d in diffs) / len(diffs))
print(f"epochs compared: {len(diffs)}; RTKLIB vs deepnav 3-D difference: rms {rms:.2f} m, max {max(diffs):.2f} m (bound 5 m)")
sys.exit(0 if max(diffs) <= 5.0 else 1)
PY
