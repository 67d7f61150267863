#!/usr/bin/env bash
# Installs the Debian 12 packages deepnav needs, only those that are missing.
#   scripts/install_deps.sh [PACKAGE...]   also the packages named (scripts/fuzz.sh: clang's)
set -euo pipefail
packages=(build-essential cmake ninja-build pkg-config libeigen3-dev libfftw3-dev libboost-dev
          libyaml-cpp-dev nlohmann-json3-dev libfmt-dev libspdlog-dev libcli11-dev
          libgtest-dev libbenchmark-dev python3-matplotlib rtklib clang-format libfec-dev
          g++-aarch64-linux-gnu qemu-user  # these two: the AArch64 correlator test (tests/cross)
          "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}" >&2
  sudo_cmd=()
  [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
