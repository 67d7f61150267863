#!/usr/bin/env bash
# Galileo E1 acquisition of the two real captures by GNSS-SDR (Debian's gnss-sdr 0.0.17),
# for comparison with `deepnav acquire --systems galileo`.
#   usage: run_gnss_sdr.sh <source dir> <scratch dir> [dwells]
# Writes gnss_sdr_<capture>_dwells<N>.txt (one line per positive acquisition, as GNSS-SDR
# logs it) into this folder. dwells (default 1): 4 ms coherent searches whose grids GNSS-SDR
# sums before its test (max_dwells; 5 is deepnav's 20 ms default). The scratch folder receives the converted inputs and GNSS-SDR's logs.
#
# Inputs as GNSS-SDR needs them:
# - 4 MHz capture: int8 I/Q with an inverted spectrum, written as gr_complex I - jQ
#   (conjugated); 500 ms, of which GNSS-SDR's file source reads 400 ms.
# - 12 MHz capture: real int8 at IF 3 MHz, written as float and repeated four times
#   (GNSS-SDR drops the last 0.1 s of a file: one 100 ms copy would give it nothing);
#   its Freq_Xlating_Fir_Filter moves IF 3 MHz to baseband.
# One channel per SVID (ChannelN.satellite), all acquiring at once, blocking, so that every
# SVID is searched from the start of the file and again after each miss.
set -euo pipefail
src=$(cd "$1" && pwd)
work=$2
dwells=${3:-1}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"

python3 - "$src/data" "$work" <<'PY'
import array, sys
data, work = sys.argv[1], sys.argv[2]
iq = array.array("b", open(f"{data}/L1_20211202_084700_4MHz_IQ.bin", "rb").read())
out = array.array("f", [0.0]) * len(iq)
out[0::2] = array.array("f", iq[0::2])
out[1::2] = array.array("f", (-q for q in iq[1::2]))
open(f"{work}/4MHz_conjugated.gr_complex", "wb").write(out.tobytes())
real = array.array("f", array.array("b", open(f"{data}/L1_20211125_004000_12MHz_I.bin", "rb").read()))
open(f"{work}/12MHz_x4.float", "wb").write(real.tobytes() * 4)
PY

channel_lines() {  # first last: one channel per SVID
  local lines=""
  for svid in $(seq "$1" "$2"); do lines+="Channel$((svid - $1)).satellite=$svid"$'\n'; done
  printf '%s' "$lines"
}

pass_filter='InputFilter.implementation=Pass_Through
InputFilter.item_type=gr_complex'
xlating_filter='InputFilter.implementation=Freq_Xlating_Fir_Filter
InputFilter.input_item_type=float
InputFilter.output_item_type=gr_complex
InputFilter.taps_item_type=float
InputFilter.number_of_taps=31
InputFilter.number_of_bands=2
InputFilter.band1_begin=0.0
InputFilter.band1_end=0.40
InputFilter.band2_begin=0.45
InputFilter.band2_end=1.0
InputFilter.ampl1_begin=1.0
InputFilter.ampl1_end=1.0
InputFilter.ampl2_begin=0.0
InputFilter.ampl2_end=0.0
InputFilter.band1_error=1.0
InputFilter.band2_error=1.0
InputFilter.filter_type=bandpass
InputFilter.grid_density=16
InputFilter.sampling_frequency=12000000
InputFilter.IF=3000000
InputFilter.decimation_factor=1'

run_part() {  # name fs item_type file filter first_svid last_svid
  local name=$1 fs=$2 item=$3 file=$4 filter=$5 first=$6 last=$7
  local part="$work/${name}_dwells$dwells/svid_${first}_$last"
  local satellites
  satellites=$(channel_lines "$first" "$last")
  mkdir -p "$part/log"
  python3 - "$here/gnss_sdr_e1_acquisition.conf" "$part/receiver.conf" <<PY
import sys
text = open(sys.argv[1]).read()
for key, value in {"@FS@": "$fs", "@ITEM_TYPE@": "$item", "@IF_FILE@": "$file", "@OUT_DIR@": "$part",
                   "@CHANNELS@": "$((last - first + 1))", "@MAX_DWELLS@": "$dwells", "@INPUT_FILTER@": """$filter""",
                   "@CHANNEL_SATELLITES@": """$satellites"""}.items():
    text = text.replace(key, value)
open(sys.argv[2], "w").write(text)
PY
  (cd "$part" && gnss-sdr --config_file=receiver.conf --log_dir=log > stdout.txt 2>&1 || true)
}

run() {  # name fs item_type file filter
  # GNSS-SDR 0.0.17 refuses 36 Galileo channels ("the maximum ... is 36"): two runs of 18.
  run_part "$@" 1 18
  run_part "$@" 19 36
  local found="$here/gnss_sdr_$1_dwells$dwells.txt"
  cat "$work/$1_dwells$dwells"/svid_*/log/gnss-sdr.*.INFO.* | grep -h "positive acquisition" \
    | sed 's/^.*positive acquisition/positive acquisition/' > "$found" || true
  echo "$1, $dwells dwells: $(wc -l < "$found") positive acquisitions"
}
run 4MHz 4000000 gr_complex "$work/4MHz_conjugated.gr_complex" "$pass_filter"
run 12MHz 12000000 float "$work/12MHz_x4.float" "$xlating_filter"
