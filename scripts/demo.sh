#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the bundled default
# scenario: synthesizes 60 s of GPS L1 C/A IF with its truth into out/demo/sim,
# runs the receiver on it into out/demo/run and prints the fix and its error.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install_deps.sh"
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$root/build" -j "$(nproc)" --target deepnav
deepnav="$root/build/tools/deepnav"
out="$root/out/demo"
"$deepnav" sim --scenario "$root/data/scenarios/default.yaml" --out "$out/sim"
echo
"$deepnav" run --input "$out/sim/if_ibyte.bin" --format ibyte --fs 4092000 --week 2190 \
  --iono-from "$root/data/brdc0010.22n" --truth "$out/sim/truth.csv" --out "$out/run"
echo
echo "Products in $out/run:"
ls -l "$out/run"
