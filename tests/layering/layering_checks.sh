#!/usr/bin/env bash
# The layering checks fail when they should: an include of the synthesizer from the receiver,
# and of the command line from the benchmark engines (scripts/check_layering.cmake); a link of
# the synthesizer by a receiver library through another target (scripts/link_layering.cmake).
# The project's own tree passes both (the build runs them; checked here too).
#   usage: layering_checks.sh <source dir>
set -uo pipefail
src=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
check() { if eval "$2"; then echo "ok   $1"; else echo "FAIL $1"; fail=1; fi; }

msg=$(cmake -DROOT="$src" -P "$src/scripts/check_layering.cmake" 2>&1); rc=$?
check "the project's includes pass (exit $rc)" '[ $rc -eq 0 ]'
msg=$(cmake -DROOT="$src/tests/layering/include_violation" -P "$src/scripts/check_layering.cmake" 2>&1); rc=$?
check "receiver including the synthesizer fails (exit $rc)" \
  '[ $rc -ne 0 ] && grep -q "receiver/reads_the_synthesizer.cpp: #include \"signals/sim/if_synthesizer.hpp\"" <<< "$msg"'
check "bench including the command line fails" \
  'grep -q "tools/bench/reads_the_cli.cpp: #include \"tools/cli/commands.hpp\"" <<< "$msg"'
msg=$(cmake -S "$src/tests/layering/link_violation" -B "$work/violation" -DDEEPNAV_SOURCE_DIR="$src" 2>&1); rc=$?
check "receiver linking the synthesizer fails (exit $rc)" \
  '[ $rc -ne 0 ] && grep -q "deepnav_receiver -> helper -> deepnav_signals_sim" <<< "$msg"'
msg=$(cmake -S "$src/tests/layering/link_clean" -B "$work/clean" -DDEEPNAV_SOURCE_DIR="$src" 2>&1); rc=$?
check "a clean link graph passes (exit $rc)" '[ $rc -eq 0 ]' || echo "$msg"
exit $fail
