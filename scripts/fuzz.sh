#!/usr/bin/env bash
# Builds the libFuzzer harnesses (tests/fuzz) with clang in build-fuzz/ and runs each one
# for a while from its seeds; prints a table and exits 1 on any finding (a crash, a
# sanitizer report, an input that hangs, an unexpected exception), naming the file that
# reproduces it (run the harness on that file alone to see it again).
#   scripts/fuzz.sh [--time SECONDS] [--jobs N] [--work DIR] [HARNESS...]
#     --time  seconds per harness (default 60)
#     --jobs  harnesses run at once (default 1)
#     --work  working corpora, logs and crash files (default build-fuzz/work; kept between
#             runs, so that every run starts from what the last ones found)
#     HARNESS names as in tests/fuzz/<name>_fuzzer.cpp (default: all)
#   DEEPNAV_BUILD_JOBS: parallel compile jobs (default: all cores)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build-fuzz"
seconds=60
jobs=1
work="$build/work"
harnesses=()
while (($#)); do
  case "$1" in
    --time) seconds=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    -*) echo "scripts/fuzz.sh: unknown option '$1'" >&2; exit 2 ;;
    *) harnesses+=("$1"); shift ;;
  esac
done
if ((${#harnesses[@]} == 0)); then
  for f in "$root"/tests/fuzz/*_fuzzer.cpp; do
    name=$(basename "$f" .cpp)
    harnesses+=("${name%_fuzzer}")
  done
fi
for h in "${harnesses[@]}"; do
  [[ -f $root/tests/fuzz/${h}_fuzzer.cpp ]] || { echo "scripts/fuzz.sh: no harness '$h' (tests/fuzz/${h}_fuzzer.cpp)" >&2; exit 2; }
done

build_start=$(date +%s)
"$root/scripts/install_deps.sh" clang libclang-rt-14-dev
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DDEEPNAV_FUZZ=ON -DDEEPNAV_WERROR=ON > /dev/null
cmake --build "$build" -j "${DEEPNAV_BUILD_JOBS:-$(nproc)}" --target "${harnesses[@]/%/_fuzzer}"
echo "fuzz build took $(($(date +%s) - build_start)) s" >&2

# The seeds of tests/fuzz/seeds.txt, each cut to its byte limit, in <work>/<harness>/seeds.
copy_seeds() {
  local h=$1 name pattern bytes file
  rm -rf "$work/$h/seeds"
  mkdir -p "$work/$h/seeds" "$work/$h/corpus"
  while read -r name pattern bytes; do
    [[ $name == "$h" ]] || continue
    for file in "$root"/$pattern; do
      if [[ -n $bytes ]]; then head -c "$bytes" "$file" > "$work/$h/seeds/$(basename "$file")"
      else cp "$file" "$work/$h/seeds/"; fi
    done
  done < <(grep -v '^#' "$root/tests/fuzz/seeds.txt")
}

# One harness: its log in <work>/<harness>/log, the file it writes on a finding in
# <work>/<harness>/ (libFuzzer's crash-*, timeout-*, leak-*, oom-*; earlier runs' stay).
run_one() {
  local h=$1
  copy_seeds "$h"
  # libFuzzer refuses a corpus folder that does not exist: a harness whose seeds all come
  # from data/ has no tests/fuzz/corpus/<harness>/ (git keeps no empty folder).
  local corpora=("$work/$h/corpus" "$work/$h/seeds")
  [[ -d $root/tests/fuzz/corpus/$h ]] && corpora+=("$root/tests/fuzz/corpus/$h")
  "$build/tests/fuzz/${h}_fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$work/$h/" "${corpora[@]}" > "$work/$h/log" 2>&1
}

start=$(date +%s)
for h in "${harnesses[@]}"; do
  while (($(jobs -rp | wc -l) >= jobs)); do wait -n || true; done
  echo "fuzzing $h for $seconds s" >&2
  run_one "$h" &
done
wait || true
elapsed=$(($(date +%s) - start))

# The table: runs and seconds from libFuzzer's final statistics, the finding's file if any.
failed=0
printf '%-20s %12s %8s  %s\n' harness runs seconds result
for h in "${harnesses[@]}"; do
  log="$work/$h/log"
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  secs=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)
  artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -1)
  result=ok
  if [[ -n $artifact ]]; then
    result="FINDING: $artifact (log: $log)"
    failed=1
  elif [[ -z $secs ]]; then
    result="FAILED to run (log: $log)"
    failed=1
  fi
  printf '%-20s %12s %8s  %s\n' "$h" "${runs:--}" "${secs:--}" "$result"
done
echo "fuzzing took ${elapsed} s (${#harnesses[@]} harnesses, ${jobs} at a time)"
exit $failed
