#!/usr/bin/env bash
# One --out folder, one writer, and no input overwritten. Two runs (or sims) into one folder
# shared *.partial names and spliced their products, one of them exiting 0: a second
# process is now refused at once, naming the folder, while the first's files stay its own;
# the partial files of a process killed outright are removed by the next one. fuse wrote its
# obs.rnx and nav.rnx over its inputs of those names, sim its scenario.yaml over the
# scenario: each is refused naming both files, the input left as it was.
#   usage: products_shared_folder.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
derive_scenario "$src/data/scenarios/default.yaml" "$work/short.yaml" 'duration_s: 2' 'sample_rate_hz: 2046000' \
  "nav_file: $brdc"
sim_scenario "$work/short.yaml" "$work/sim"
sim_source source "$work/sim"

# --- inputs ---------------------------------------------------------------------------
walk=$src/data/walk_0827
mkdir "$work/fuse_self"
cp "$walk/walk.obs" "$work/fuse_self/obs.rnx"
cp "$walk/walk.nav" "$work/fuse_self/nav.rnx"
EXIT_STATUS=1 expect_failure "fuse --out the inputs' folder" \
  "--out '$work/fuse_self': its product obs.rnx would replace the input '$work/fuse_self/obs.rnx' (--obs)" -- \
  "$deepnav" -q fuse --config "$walk/walk.yaml" --obs "$work/fuse_self/obs.rnx" --nav "$work/fuse_self/nav.rnx" \
  --out "$work/fuse_self"
check "fuse: obs.rnx unchanged" 'cmp -s "$walk/walk.obs" "$work/fuse_self/obs.rnx"'
check "fuse: nav.rnx unchanged" 'cmp -s "$walk/walk.nav" "$work/fuse_self/nav.rnx"'
check "fuse: nothing written" '[[ $(ls "$work/fuse_self" | wc -l) -eq 2 ]]'

mkdir "$work/sim_self"
cp "$work/short.yaml" "$work/sim_self/scenario.yaml"
EXIT_STATUS=1 expect_failure "sim --out the scenario's folder" \
  "--out '$work/sim_self': its product scenario.yaml would replace the input '$work/sim_self/scenario.yaml' (--scenario)" \
  -- "$deepnav" -q sim --scenario "$work/sim_self/scenario.yaml" --out "$work/sim_self"
check "sim: scenario.yaml unchanged" 'cmp -s "$work/short.yaml" "$work/sim_self/scenario.yaml"'
check "sim: nothing written" '[[ $(ls "$work/sim_self") == scenario.yaml ]]'

mkdir "$work/run_self"
cp "$brdc" "$work/run_self/nav.rnx"
EXIT_STATUS=1 expect_failure "run --ephemeris-from a file in --out named as a product" \
  "its product nav.rnx would replace the input '$work/run_self/nav.rnx' (--ephemeris-from)" -- \
  "$deepnav" -q run "${source[@]}" --ephemeris-from "$work/run_self/nav.rnx" --out "$work/run_self"
check "run: nav.rnx unchanged" 'cmp -s "$brdc" "$work/run_self/nav.rnx"'
EXIT_STATUS=1 expect_failure "acquire --json its own input" \
  "--json '$work/sim/if_ibyte.bin' would replace the input '$work/sim/if_ibyte.bin'" -- \
  "$deepnav" -q acquire "${source[@]:0:6}" --json "$work/sim/if_ibyte.bin"

# --- one writer per folder --------------------------------------------------------------
# A long synthesis holds its folder; a run and a sim into it are refused while it goes on.
derive_scenario "$src/data/scenarios/default.yaml" "$work/long.yaml" 'duration_s: 300'
start_background holder "$deepnav" -q sim --scenario "$work/long.yaml" --out "$work/shared" --threads 1
for _ in $(seq 100); do compgen -G "$work/shared/*.partial" > /dev/null && break; sleep 0.1; done
in_use="output folder '$work/shared' is in use: another deepnav process is writing its products there"
EXIT_STATUS=1 LIMIT_S=10 expect_failure "a run into a folder in use" "$in_use" -- \
  "$deepnav" -q run "${source[@]}" --out "$work/shared"
EXIT_STATUS=1 LIMIT_S=10 expect_failure "a sim into a folder in use" "$in_use" -- \
  "$deepnav" -q sim --scenario "$work/short.yaml" --out "$work/shared"
check "the holder's files are its own: partial files of one process" \
  '[[ $(ls "$work/shared" | sed -n "s/.*\.\([0-9]*\)\.partial$/\1/p" | sort -u) == "$holder" ]]'

# Killed outright, it leaves its partial files; the next process there removes them.
kill -KILL $holder
reap $holder || true
check "SIGKILL leaves partial files" 'compgen -G "$work/shared/*.partial" > /dev/null'
"$deepnav" sim --scenario "$work/short.yaml" --out "$work/shared" > /dev/null 2> "$work/after_kill.err" ||
  abort "sim after the kill: $(cat "$work/after_kill.err")"
check "the next sim removed them" '! ls "$work/shared" | grep -q partial'
check "and said so" 'grep -q "removed .*\.partial., left by a run that was killed" "$work/after_kill.err"'
check "its files are complete" '[[ -s $work/shared/if_ibyte.bin && -s $work/shared/synthesis.json ]]'
finish
