#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the bundled default
# scenario: synthesizes 30 s of GPS L1 C/A IF with its truth into out/demo and
# prints what it wrote.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install_deps.sh"
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$root/build" -j "$(nproc)" --target deepnav
out="$root/out/demo"
"$root/build/tools/deepnav" sim --scenario "$root/data/scenarios/default.yaml" --out "$out"
echo
echo "Files in $out:"
ls -l "$out"
echo
echo "First truth rows ($out/truth.csv):"
head -3 "$out/truth.csv" | cut -d, -f1-12
