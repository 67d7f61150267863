#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the bundled default scenario.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install_deps.sh"
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$root/build" -j "$(nproc)" --target deepnav
"$root/build/tools/deepnav" --help
