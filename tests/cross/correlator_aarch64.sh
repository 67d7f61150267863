#!/usr/bin/env bash
# The correlator's NEON kernel on AArch64 without ARM hardware: cross-compiles the C/A and E1
# correlators, the C/A and E1 codes and the correlator tests (with GoogleTest from its
# sources) with Debian's aarch64 cross compiler and runs them under qemu-user. Every kernel
# the emulated CPU has (portable and NEON) must give the portable kernel's integers.
#   correlator_aarch64.sh <source dir> <work dir>
# Exit 77 (ctest: skipped) with a message when the cross compiler, qemu or the GoogleTest
# sources are missing (scripts/install_deps.sh installs them).
set -euo pipefail
src=$1
work=$2
cxx=aarch64-linux-gnu-g++
qemu=qemu-aarch64
gtest=/usr/src/googletest/googletest
missing=()
command -v "$cxx" >/dev/null || missing+=("$cxx (package g++-aarch64-linux-gnu)")
command -v "$qemu" >/dev/null || missing+=("$qemu (package qemu-user)")
[[ -f $gtest/src/gtest-all.cc ]] || missing+=("$gtest (package libgtest-dev)")
if ((${#missing[@]})); then
  list=$(printf '%s, ' "${missing[@]}")
  echo "SKIPPED: the AArch64 correlator test needs ${list%, }; scripts/install_deps.sh installs them"
  exit 77
fi
mkdir -p "$work"
cd "$work"
launcher=()
command -v ccache >/dev/null && launcher=(ccache)
# fmt header-only: the cross toolchain has no aarch64 libfmt to link.
flags=(-O2 -std=c++20 -Wall -Wextra -Werror -DFMT_HEADER_ONLY -I"$src")
objects=()
for f in receiver/tracking/correlator.cpp receiver/tracking/kernels/kernel_portable.cpp receiver/tracking/kernels/kernel_neon.cpp \
         receiver/tracking/e1_correlator.cpp signals/ca_code.cpp signals/galileo/e1_codes.cpp \
         signals/galileo/e1_code_tables.cpp signals/galileo/e1_modulation.cpp signals/sim/gaussian_noise.cpp \
         signals/sim/satellite_signal_kernel.cpp tests/receiver/correlator_test.cpp tests/receiver/e1_correlator_test.cpp; do
  o=$(echo "$f" | tr / _).o
  "${launcher[@]}" "$cxx" "${flags[@]}" -c "$src/$f" -o "$o"
  objects+=("$o")
done
for f in gtest-all gtest_main; do  # GoogleTest itself: built once per work dir
  [[ -f $f.o ]] || "${launcher[@]}" "$cxx" -O1 -std=c++20 -I"$gtest" -I"$gtest/include" -c "$gtest/src/$f.cc" -o "$f.o"
  objects+=("$f.o")
done
# Static, so that qemu needs no AArch64 libraries; the linker's getaddrinfo note is GoogleTest's.
"$cxx" -static -o correlator_tests_aarch64 "${objects[@]}" -pthread 2>link.log || { cat link.log; exit 1; }
cd "$src"
"$qemu" "$work/correlator_tests_aarch64" --gtest_brief=1
