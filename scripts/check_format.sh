#!/usr/bin/env bash
# Checks every tracked C++ file against .clang-format (clang-format 14, Debian 12) and names
# the files that differ; --fix rewrites them instead.
#   scripts/check_format.sh [--fix]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
fix=0
for arg in "$@"; do
  case "$arg" in
    --fix) fix=1 ;;
    *) echo "scripts/check_format.sh: unknown option '$arg' (expected --fix)" >&2; exit 2 ;;
  esac
done
command -v clang-format >/dev/null || { echo "scripts/check_format.sh: clang-format is missing (scripts/install_deps.sh installs it)" >&2; exit 2; }
mapfile -t files < <(git ls-files '*.cpp' '*.hpp')
if ((fix)); then
  clang-format -i "${files[@]}"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if ((${#bad[@]})); then
  echo "not formatted as .clang-format says (scripts/check_format.sh --fix rewrites them):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "format: ${#files[@]} C++ files as .clang-format says"
