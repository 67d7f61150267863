#!/usr/bin/env bash
# Ultra-tight on a weak signal (`bench threshold --modes ultra`, the land circle with a
# tactical IMU, C/N0 45 dB-Hz until 25 s then falling 0.5 dB/s to 5 dB-Hz): with the data
# bits wiped off and 200 ms coherent integrations it keeps a 10 m solution from at least
# four satellites' measurements to 13 dB-Hz or below (the scalar loops lose it near 29); the
# report names the integration used; a coherent length that is not a multiple of a data
# bit is rejected.
#   usage: ultra_weak_signal.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
ramp=(bench threshold --modes ultra --start 45 --ramp-start 25 --end 5 --rate 0.5 --work-dir "$work")
"$deepnav" -q "${ramp[@]}" --json "$work/long.json" > "$work/long.txt" 2>&1 || abort "long run: $(cat "$work/long.txt")"
expect_failure "--coherent-ms 50 rejected" "multiple of 20 ms" -- "$deepnav" "${ramp[@]}" --coherent-ms 50
check_json_each "$work/long.json" \
  "200 ms data-wiped: holds to 13 dB-Hz or below" rows.0.threshold_dbhz '<=' 13.0 \
  "within 10 m while it holds" rows.0.max_h_error_before_m '<' 10.0 \
  "the report names the coherent length" notes.coherent_ms '==' 200 \
  "the report names the integration" notes.ultra_integration contains '"200 ms coherent"'
finish
