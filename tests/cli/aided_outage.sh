#!/usr/bin/env bash
# A 30 s outage of every signal in the middle of paper 003's land circle, with a
# tactical IMU: in ultra-tight and in tight mode the INS coasts through the gap (error
# reported and bounded), every channel is tracked again within 1 s of the signals'
# return, and the solution is back to sub-metre level right after. With
# --max-solution-sigma 1.2 the end of the coast, whose own 1-sigma passes 1.2 m, is withheld
# (summary.json withheld_solutions) and every epoch after the return is published again.
# Through the outage the solutions are labelled coast (GGA quality 6), not ultra or tight.
#   usage: aided_outage.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
sim_scenario "$src/data/scenarios/land_circle_outage_120s.yaml" "$work/sim"
sim_imu imu "$work/sim"
aided=(--iono-from "$brdc" --truth "$work/sim/truth.csv" "${imu[@]}")
run_on_sim "$work/sim" "$work/ultra" "${aided[@]}" --mode ultra
run_on_sim "$work/sim" "$work/tight" "${aided[@]}" --mode tight
run_on_sim "$work/sim" "$work/tight_withheld" "${aided[@]}" --mode tight --max-solution-sigma 1.2
check_py "coasting through the outage, back after it" -m checks.aided_outage "$work/sim" "$work"
finish
