#!/usr/bin/env bash
# Paper 003's land circle through the receiver: every synthesized satellite is tracked
# from the start to the end of the run (never lost), and the fixes follow the circle.
#   usage: receiver_land_circle.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
sim_scenario "$src/data/scenarios/land_circle_60s.yaml" "$work/sim"
run_on_sim "$work/sim" "$work/run" --iono-from "$brdc" --truth "$work/sim/truth.csv"
check_py "every satellite tracked throughout, fixes on the circle" -m checks.receiver_land_circle "$work/sim" "$work/run"
finish
