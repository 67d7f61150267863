#!/usr/bin/env bash
# IF without troposphere and without ionosphere, the receiver's default models: the aided
# modes find the troposphere's mismatch, then the ionosphere's fitted beside it, take both
# states and stay ahead of loose coupling (lib/atmosphere_mismatch.sh).
#   usage: aided_atmosphere_mismatch.sh <deepnav binary> <source dir>
exec bash "$(dirname "$0")/lib/atmosphere_mismatch.sh" "$1" "$2" atmosphere
