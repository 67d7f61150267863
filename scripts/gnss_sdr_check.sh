#!/usr/bin/env bash
# Independent check of the IF synthesizer: GNSS-SDR (Debian package gnss-sdr)
# processes a 60 s `deepnav sim` static scenario and its position fixes are
# compared with the synthesizer's truth. Passes when every GNSS-SDR fix after the
# first 5 lies within 10 m (3-D) of the true position.
#   usage: scripts/gnss_sdr_check.sh [scenario.yaml] [work_dir]   (DEEPNAV=path overrides the binary)
# Not part of the default test suite (it takes a few minutes and needs gnss-sdr).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
scenario=${1:-$root/data/scenarios/gnss_sdr_static.yaml}
work=${2:-$root/out/gnss_sdr_check}
command -v gnss-sdr >/dev/null || { echo "gnss-sdr is not installed: apt-get install gnss-sdr" >&2; exit 2; }
deepnav=${DEEPNAV:-$root/build/tools/deepnav}
if [[ ! -x $deepnav ]]; then
  cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$root/build" --target deepnav
fi
rm -rf "$work" && mkdir -p "$work/gnss_sdr"
"$deepnav" sim --scenario "$scenario" --out "$work/sim"
if_file=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["if_file"])' "$work/sim/synthesis.json")
fs=$(python3 -c 'import json,sys; print(int(json.load(open(sys.argv[1]))["sample_rate_hz"]))' "$work/sim/synthesis.json")
fmt_=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["format"])' "$work/sim/synthesis.json")
[[ $fmt_ == ishort ]] || { echo "the GNSS-SDR configuration expects format ishort, scenario gives $fmt_" >&2; exit 2; }
sed -e "s|@FS@|$fs|g" -e "s|@IF_FILE@|$work/sim/$if_file|g" -e "s|@OUT_DIR@|$work/gnss_sdr|g" \
  "$root/scripts/gnss_sdr/gps_l1_ishort.conf" > "$work/gnss_sdr/receiver.conf"
(cd "$work/gnss_sdr" && gnss-sdr --config_file=receiver.conf > gnss_sdr.log 2>&1) || true
python3 "$root/tools/utils/compare_nmea_to_truth.py" "$work/gnss_sdr/gnss_sdr_pvt.nmea" "$work/sim/truth.csv" --max-error-m 10
