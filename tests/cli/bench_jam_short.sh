#!/usr/bin/env bash
# A short jamming sweep (20 s scenario at 2.6 Msps, CW from 14 s at J/S 20 and 60 dB,
# with and without excision, two jobs): the unmitigated receiver keeps its fix at 20 dB
# and loses it at 60 dB, excision keeps it at 60 dB; a second run finds every point
# finished; --list-commands prints one command per unfinished point; an unknown receiver
# mode is rejected naming the available ones, an aided mode on a scenario without an IMU
# is rejected; one ultra-tight point (CW at 20 dB) passes with its solution from the
# ultra-tight filter for the whole jammed window.
#   usage: bench_jam_short.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
scenario=$src/data/scenarios/jam_short_test.yaml
sweep=(bench jam --scenario "$scenario" --jammer cw --js 20:60:40 --mitigation none,excision --onset 14
       --out "$work/sweep")
expect_failure "unknown mode rejected" "unknown receiver mode 'vector' (available: scalar, loose, tight, ultra)" -- \
  "$deepnav" "${sweep[@]}" --modes scalar,vector
expect_failure "aided mode without an IMU rejected" "needs an IMU" -- "$deepnav" bench jam \
  --scenario "$src/data/scenarios/static_120s.yaml" --jammer cw --js 20 --modes tight --out "$work/noimu" --list-commands
listed=$("$deepnav" "${sweep[@]}" --list-commands)
check "4 commands listed" '[[ $(grep -c "bench jam-point" <<< "$listed") -eq 4 ]]'
"$deepnav" "${sweep[@]}" --jobs 2 --no-plots > "$work/first.txt" 2>&1 || abort "sweep: $(cat "$work/first.txt")"
second=$("$deepnav" "${sweep[@]}" --jobs 2 --no-plots 2>&1)
check "resume: nothing rerun" 'grep -q "4 already finished" <<< "$second" && grep -q "0 to run" <<< "$second"'
listed=$("$deepnav" "${sweep[@]}" --list-commands)
check "nothing left to list" '[[ -z $listed ]]'
# One ultra-tight point into the same folder; the report then covers all five.
"$deepnav" bench jam --scenario "$scenario" --jammer cw --js 20 --modes ultra --mitigation none --onset 14 \
  --out "$work/sweep" > "$work/ultra.txt" 2>&1 || abort "ultra sweep: $(cat "$work/ultra.txt")"
thresholds=$work/sweep/thresholds.md
check "thresholds.md written, with the scalar excision and the ultra rows" '[[ -s $thresholds ]] &&
  grep -q "| jam_short_test | cw | scalar | excision |" "$thresholds" && grep -q "| jam_short_test | cw | ultra | none |" "$thresholds"'
if /usr/bin/python3 -c "import matplotlib" 2> /dev/null; then
  check "plot written" '[[ -s $work/sweep/jam_cw.png ]]'
fi
check_py "the sweep's findings" -m checks.bench_jam_short "$work/sweep"
[[ $harness_failures -eq 0 ]] || cat "$work/first.txt"
finish
