#!/usr/bin/env bash
# IF without troposphere, the receiver's default models: the aided modes find the mismatch,
# take the troposphere state and stay ahead of loose coupling (lib/atmosphere_mismatch.sh).
#   usage: aided_troposphere_mismatch.sh <deepnav binary> <source dir>
exec bash "$(dirname "$0")/lib/atmosphere_mismatch.sh" "$1" "$2" troposphere
