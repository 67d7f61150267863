#!/usr/bin/env bash
# The correlator on an x86-64 CPU with AVX2 and no AVX-512 (most laptops, desktops and CI
# runners), whatever CPU runs the suite: the receiver's correlator tests under qemu-user
# emulating a Haswell (AVX2 + FMA). The dispatch must find AVX2 the fastest kernel, the
# AVX2 kernel must give the portable kernel's integers, and every AVX-512 case must be
# reported as skipped, not passed. (Emulation says nothing about speed.)
#   correlator_avx2_only.sh <receiver_tests binary>
# Exit 77 (ctest: skipped) with a message where qemu-x86_64 is missing or the host is not
# x86-64 (scripts/install_deps.sh installs qemu-user).
set -uo pipefail
tests=$1
qemu=qemu-x86_64
if [[ $(uname -m) != x86_64 ]]; then
  echo "SKIPPED: the AVX2-only correlator test emulates an x86-64 CPU for an x86-64 build; this host is $(uname -m)"
  exit 77
fi
if ! command -v "$qemu" > /dev/null; then
  echo "SKIPPED: the AVX2-only correlator test needs $qemu (package qemu-user); scripts/install_deps.sh installs it"
  exit 77
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
"$qemu" -cpu Haswell "$tests" --gtest_filter='Correlator*' > "$log" 2>&1
status=$?
bad=()
((status == 0)) || bad+=("the correlator tests failed under $qemu -cpu Haswell (exit $status)")
for t in IsBitExactWithThePortableKernelWithAndWithoutTheNoiseTap CanBeChosenForTheWholeProgram; do
  grep -q "^\[       OK \] Correlator/EveryKernel.$t/avx2 " "$log" || bad+=("$t/avx2 did not pass")
  grep -q "^\[  SKIPPED \] Correlator/EveryKernel.$t/avx512 " "$log" || bad+=("$t/avx512 was not reported as skipped")
done
grep -q "^\[       OK \] Correlator.TheFastestKernelIsTheNativeSimdOne " "$log" || bad+=("the fastest kernel is not the AVX2 one")
if ((${#bad[@]})); then
  tail -40 "$log"
  printf 'FAIL: %s\n' "${bad[@]}"
  exit 1
fi
grep -E "^\[  (PASSED|SKIPPED) \] [0-9]+ test" "$log"
echo "ok: AVX2 kernel bit-exact and chosen, AVX-512 cases skipped, on an emulated AVX2-only CPU"
