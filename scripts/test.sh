#!/usr/bin/env bash
# Installs what is missing, checks the C++ formatting (scripts/check_format.sh), builds and
# runs the whole test suite with ctest.
#   scripts/test.sh              Release build in build/
#   scripts/test.sh --sanitize   ASan+UBSan build in build-sanitize/
# Then a brief fuzzing stage (scripts/fuzz.sh): every harness for DEEPNAV_FUZZ_SECONDS
# (default 10), two at a time; DEEPNAV_FUZZ_SECONDS=0 skips it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build"
cmake_args=(-DDEEPNAV_WERROR=ON)
for arg in "$@"; do
  case "$arg" in
    --sanitize) build="$root/build-sanitize"; cmake_args+=(-DDEEPNAV_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDEEPNAV_BUILD_BENCHMARKS=OFF) ;;
    *) echo "scripts/test.sh: unknown option '$arg' (expected --sanitize)" >&2; exit 2 ;;
  esac
done
"$root/scripts/install_deps.sh"
"$root/scripts/check_format.sh"
jobs=$(nproc)
cmake -S "$root" -B "$build" -G Ninja "${cmake_args[@]}"
cmake --build "$build" -j "$jobs"
(cd "$build" && ctest --output-on-failure -j "$jobs" --timeout 600)
fuzz_seconds=${DEEPNAV_FUZZ_SECONDS:-10}
if ((fuzz_seconds > 0)); then
  "$root/scripts/fuzz.sh" --time "$fuzz_seconds" --jobs 2
fi
