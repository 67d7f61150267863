# Shared set-up of the command-line tests, sourced first by every tests/cli/*.sh:
#   source "$(dirname "$0")/lib/harness.sh" "$@"
# The arguments are the test's own (<deepnav binary> <source dir>). It gives
#   deepnav, src, work    the binary, the source tree and a fresh folder removed at exit
#                         (kept with KEEP_WORK=1, its path printed)
#   check NAME CONDITION  evaluates CONDITION (a shell expression), prints ok/FAIL NAME and
#                         remembers a failure; finish exits with the verdict
#   abort MESSAGE         a set-up step failed: FAIL MESSAGE, exit 1 at once
# and the helpers below for simulating, running the receiver, servers, expected failures
# and the products (read by the Python in ../pylib, which PYTHONPATH names). Functions that
# set a variable the caller names keep their own names ending in _, so as not to hide it.

set -Eeuo pipefail
shopt -s inherit_errexit
# A command that fails outside a condition ends the test naming the line and the command.
trap 'echo "FAIL ${BASH_SOURCE[0]##*/}:$LINENO: \`$BASH_COMMAND\` exited $?" >&2' ERR

[[ $# -ge 1 ]] || { echo "usage: ${0##*/} <deepnav binary> <source dir>" >&2; exit 2; }
deepnav=$(realpath "$1")
src=$(realpath "${2:-.}")
cli_tests=$src/tests/cli
# py ARGUMENTS: the Python of tests/cli/pylib (standard library only) on the interpreter
# PATH names, resolved once (a version manager's shim costs a process at every call), and
# without site's start-up (a .pth there may import packages, tens of ms at every call).
python=$(python3 -c 'import sys; print(sys.executable)')
py() { "$python" -S "$@"; }
export PYTHONPATH="$cli_tests/pylib${PYTHONPATH:+:$PYTHONPATH}"
export PYTHONDONTWRITEBYTECODE=1
# The bundled broadcast file and IMU grades (assisted starts, the aided modes).
brdc=$src/data/brdc0010.22n
imu_grades=$src/data/imu_grades.yaml
assisted=(--ephemeris-from "$brdc" --iono-from "$brdc")

work=$(mktemp -d)
harness_failures=0
harness_background=()
harness_cleanup() {
  local pid
  for pid in "${harness_background[@]}"; do kill "$pid" 2>/dev/null || true; done
  if [[ -n ${KEEP_WORK:-} ]]; then echo "work folder kept: $work"; else rm -rf "$work"; fi
}
trap harness_cleanup EXIT

# --- verdicts -------------------------------------------------------------------------

# pass and fail print a verdict and set last_check (ok or FAIL): a follow-up check may
# depend on it: if [[ $last_check == ok ]]; then check ...; fi
pass() { echo "ok   $*"; last_check=ok; }
fail() { echo "FAIL $*"; last_check=FAIL; harness_failures=$((harness_failures + 1)); }
abort() { echo "FAIL $*" >&2; exit 1; }

check() {  # check NAME CONDITION
  if eval "$2"; then pass "$1"; else fail "$1"; fi
}

# check_py NAME PYTHON_ARGUMENTS...: a Python check that prints its own lines and exits non-zero
# when it failed (the modules of ../pylib/checks).
check_py() {
  local name=$1
  shift
  if py "$@"; then pass "$name"; else fail "$name"; fi
}

# check_json NAME FILE PATH OP VALUE: one value of a JSON product against a bound, e.g.
#   check_json "horizontal RMS <= 3 m" "$run/summary.json" horizontal_error_m.rms '<=' 3
# (pylib/query.py: PATH a.b.0.c, . or len(PATH); OP == != < <= > >= contains lacks; VALUE
# JSON). check_json_each FILE NAME PATH OP VALUE [NAME PATH OP VALUE]... makes several
# checks of one file in one Python start.
check_json() { check_json_each "$2" "$1" "${@:3}"; }

check_json_each() {
  local output status=0 line counted=0
  output=$(py -m query check-each "$@" 2>&1) || status=$?
  while IFS= read -r line; do
    case $line in
      "ok   "*) echo "$line"; last_check=ok ;;
      "FAIL "*) echo "$line"; last_check=FAIL; counted=$((counted + 1)); harness_failures=$((harness_failures + 1)) ;;
    esac
  done <<< "$output"
  if [[ $status -ne 0 && $counted -eq 0 ]]; then fail "check_json_each $*: $output"; fi
}

json_value() { py -m query get "$@"; }  # json_value FILE PATH: the value, JSON for containers

finish() {  # the verdict of every check so far
  if [[ $harness_failures -eq 0 ]]; then echo "PASS ${0##*/}"; exit 0; fi
  echo "FAIL ${0##*/}: $harness_failures check(s) failed"
  exit 1
}

# --- expected failures ----------------------------------------------------------------

# expect_failure NAME [--ordered|--grep] FRAGMENT... -- COMMAND...: COMMAND must exit
# non-zero with every FRAGMENT in its output (stdout and stderr; in that order with
# --ordered; with --grep each FRAGMENT is a grep pattern).
# Options from the environment: LIMIT_S (it must also end within that many seconds, under
# `timeout`), EXIT_STATUS (exactly that status), ADDRESS_SPACE_KB (run under ulimit -v).
# Sets failure_output and failure_status, and last_check as pass and fail do.
expect_failure() {
  local name=$1 how=literal
  shift
  case ${1:-} in --ordered | --grep) how=${1#--}; shift ;; esac
  local fragments=()
  while [[ $1 != -- ]]; do fragments+=("$1"); shift; done
  shift
  local start_us=${EPOCHREALTIME//[.,]/}
  failure_status=0
  failure_output=$(
    ulimit -v "${ADDRESS_SPACE_KB:-unlimited}"
    if [[ -n ${LIMIT_S:-} ]]; then timeout -k 2 "$LIMIT_S" "$@" 2>&1; else "$@" 2>&1; fi
  ) || failure_status=$?
  local tenths=$(((${EPOCHREALTIME//[.,]/} - start_us) / 100000)) rest=$failure_output fragment
  if [[ $failure_status -eq 0 ]]; then fail "$name: exit status 0: $failure_output"; return; fi
  if [[ -n ${LIMIT_S:-} && ($failure_status -eq 124 || $failure_status -eq 137) ]]; then
    fail "$name: still running after $LIMIT_S s"; return
  fi
  if [[ -n ${EXIT_STATUS:-} && $failure_status -ne $EXIT_STATUS ]]; then
    fail "$name: exit status $failure_status, expected $EXIT_STATUS: $failure_output"; return
  fi
  for fragment in "${fragments[@]}"; do
    if [[ $how == grep ]] && grep -q -e "$fragment" <<< "$failure_output"; then continue; fi
    if [[ $how != grep && $rest == *"$fragment"* ]]; then
      [[ $how == literal ]] || rest=${rest#*"$fragment"}
      continue
    fi
    fail "$name: message lacks '$fragment': $failure_output"
    return
  done
  pass "$name (exit $failure_status, $((tenths / 10)).$((tenths % 10)) s): ${failure_output%%$'\n'*}"
}

# --- scenarios and the simulator ------------------------------------------------------

# derive_scenario BASE OUT 'key: value'... [--append 'key: value'...]: BASE with those
# top-level keys replaced (each must be there) and the --append ones added.
derive_scenario() { py -m scenario_edit "$@"; }

# sim_scenario SCENARIO OUT [sim options]: synthesizes into OUT (log in OUT.log); a failed
# synthesis ends the test with its log.
sim_scenario() {
  local scenario=$1 out=$2
  shift 2
  "$deepnav" -q sim --scenario "$scenario" --out "$out" "$@" > "$out.log" 2>&1 ||
    abort "sim $scenario $*: $(tail -n 5 "$out.log")"
}

# scenario_value FILE KEY: the one-line value of a top-level key of a scenario file.
scenario_value() {
  local value
  value=$(awk -v key="$2:" 'index($0, key) == 1 { sub(/^[^:]*:[ \t]*/, ""); sub(/[ \t]*(#.*)?$/, ""); print; exit }' "$1")
  [[ -n $value ]] || abort "${1##*/}: no top-level '$2:'"
  echo "$value"
}

sample_rate_of() { py -m query get "$1/synthesis.json" sample_rate_hz --integer; }  # SIM_DIR
week_of() { py -m query get "$1/synthesis.json" start_gps_week; }  # SIM_DIR: the GPS week it starts in

# sim_source VAR SIM_DIR: VAR becomes the receiver's source options for the sim's IF file
# (--input, --format, --fs and --week, all from its synthesis.json).
sim_source() {
  local -n source_options_=$1
  mapfile -t source_options_ < <(py -m query source "$2")
  [[ ${#source_options_[@]} -eq 8 ]] || abort "no source options from $2/synthesis.json"
}

# sim_imu VAR SIM_DIR: VAR becomes the options of the sim's IMU (its imu.csv, and the
# grade and lever arm its scenario.yaml records), with the bundled grades file.
sim_imu() {
  local -n imu_options_=$1
  local sim_=$2 imu_line_ grade_ x_ y_ z_
  imu_line_=$(py -m query imu "$sim_/scenario.yaml")
  read -r grade_ x_ y_ z_ <<< "$imu_line_"
  imu_options_=(--imu "$sim_/imu.csv" --imu-grade "$grade_" --imu-grades-file "$imu_grades" \
    --imu-lever-arm "$x_" "$y_" "$z_")
}

# --- the receiver ---------------------------------------------------------------------

# run_receiver OUT [run options]: `deepnav -q run --out OUT ...`, its output in OUT.log; a
# failed run ends the test with the log's end.
run_receiver() {
  local out=$1
  shift
  "$deepnav" -q run --out "$out" "$@" > "$out.log" 2>&1 || abort "run --out ${out##*/} $*: $(tail -n 5 "$out.log")"
}

# run_on_sim SIM_DIR OUT [run options]: run_receiver on the sim's IF file (sim_source).
run_on_sim() {
  local sim=$1 out=$2
  shift 2
  local run_source_
  sim_source run_source_ "$sim"
  run_receiver "$out" "${run_source_[@]}" "$@"
}

# same_product A B: two runs' copies of one product are the same byte for byte, except
# summary.json's `resources` (peak memory, CPU seconds: what the machine did).
same_product() {
  if [[ ${1##*/} == summary.json ]]; then
    py -m query same "$1" "$2" --ignore resources > /dev/null
  else
    cmp -s "$1" "$2"
  fi
}

# check_same_products NAME DIR_A DIR_B: every product of DIR_A is in DIR_B and the same
# (same_product), and DIR_B has no other.
check_same_products() {
  local name=$1 a=$2 b=$3 file differ=()
  for file in "$a"/*; do same_product "$file" "$b/${file##*/}" || differ+=("${file##*/}"); done
  for file in "$b"/*; do [[ -e $a/${file##*/} ]] || differ+=("${file##*/} (only in ${b##*/})"); done
  if [[ ${#differ[@]} -eq 0 ]]; then pass "$name: $(ls "$a" | wc -l) products identical"; else fail "$name: ${differ[*]} differ"; fi
}

# --- servers and peers ----------------------------------------------------------------

# start_background VAR COMMAND...: runs COMMAND in the background, its pid in VAR; it is
# killed at exit unless reaped first (reap).
start_background() {
  local -n background_pid_=$1
  shift
  "$@" &
  background_pid_=$!
  harness_background+=("$background_pid_")
}

# reap PID: waits for a background command and returns its exit status.
reap() {
  local pid=$1 status=0 kept=() p
  wait "$pid" || status=$?
  for p in "${harness_background[@]}"; do [[ $p == "$pid" ]] || kept+=("$p"); done
  harness_background=("${kept[@]}")
  return $status
}

# port_from FILE [tcp|udp]: the port a server writes to FILE once it listens ("tcp N" and
# "udp N" lines, or the number alone without a kind); waits up to 10 s, aborts without one.
port_from() {
  local file=$1 kind=${2:-} port=
  for _ in $(seq 100); do [[ -s $file ]] && break; sleep 0.1; done
  if [[ -z $kind ]]; then
    port=$(cat "$file" 2>/dev/null || true)
  else
    port=$(awk -v kind="$kind" '$1 == kind {print $2}' "$file" 2>/dev/null || true)
  fi
  [[ -n $port ]] || abort "no ${kind:-} port in ${file##*/} after 10 s"
  echo "$port"
}

peers=$cli_tests/pylib/peers  # the Python stand-ins for the other end of a stream
