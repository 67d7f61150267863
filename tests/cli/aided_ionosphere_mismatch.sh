#!/usr/bin/env bash
# IF without ionosphere, the receiver's default models: the aided modes find the mismatch,
# take the ionosphere state and stay ahead of loose coupling (lib/atmosphere_mismatch.sh).
#   usage: aided_ionosphere_mismatch.sh <deepnav binary> <source dir>
exec bash "$(dirname "$0")/lib/atmosphere_mismatch.sh" "$1" "$2" ionosphere
