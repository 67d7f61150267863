#!/usr/bin/env bash
# Runs a command with a small tmpfs mounted for it alone, in a mount namespace of its own
# (so nothing stays mounted, whatever happens), and copies out what the command left there.
#   in_tmpfs.sh SIZE MOUNT_POINT COPY_TO -- COMMAND...
# The command's exit status goes to COPY_TO.status, its stdout and stderr to COPY_TO.log,
# the tmpfs's content to COPY_TO/. As root the namespace is a plain mount namespace; as
# another user, a user namespace's root mounts the tmpfs where the kernel allows it. Exits
# 77 when no tmpfs can be mounted here (the caller skips what needs one).
#   in_tmpfs.sh --probe MOUNT_POINT: exit 0 when a tmpfs can be mounted there, else 77
set -euo pipefail
if [[ $(id -u) -eq 0 ]]; then namespace=(unshare --mount); else namespace=(unshare --user --map-root-user --mount); fi
if [[ ${1:-} == --probe ]]; then
  "${namespace[@]}" mount -t tmpfs -o size=64k tmpfs "$2" 2> /dev/null || exit 77
  exit 0
fi
if [[ ${IN_TMPFS_NAMESPACE:-} != 1 ]]; then
  export IN_TMPFS_NAMESPACE=1
  exec "${namespace[@]}" "$0" "$@"
fi
size=$1 mount_point=$2 copy_to=$3
shift 4  # SIZE MOUNT_POINT COPY_TO --
mount -t tmpfs -o "size=$size" tmpfs "$mount_point" || exit 77
status=0
"$@" > "$copy_to.log" 2>&1 || status=$?
echo "$status" > "$copy_to.status"
mkdir -p "$copy_to"
cp -a "$mount_point/." "$copy_to/"
