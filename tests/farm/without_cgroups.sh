#!/usr/bin/env bash
# The farm test in a mount namespace whose /sys/fs/cgroup is an empty tmpfs, as in a container or
# a chroot without a cgroup file system (slurmd once failed to start there).
#   without_cgroups.sh SOURCE_DIR ARBOR
# Where no mount namespace can be made (a chroot, an unprivileged container) this machine is itself
# such a place when it has no cgroup file system, and the plain farm test (farm.slurm_plan_merges_
# bit_exact) already runs there; otherwise the condition cannot be made here: exit 77, which ctest
# reports as skipped, with the reason.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
if unshare -m true 2>/dev/null; then
  exec unshare -m bash -c 'mount -t tmpfs tmpfs /sys/fs/cgroup && exec bash "$0" "$1" "$2"' \
    "$here/slurm_test.sh" "$1" "$2"
fi
if ! grep -qs ' /sys/fs/cgroup' /proc/mounts; then
  echo "farm test without cgroups: no mount namespace here, and none is needed: this machine has no cgroup file system" >&2
  exec bash "$here/slurm_test.sh" "$1" "$2"
fi
echo "farm test without cgroups: skipped: this machine has a cgroup file system and allows no mount namespace (unshare -m) to hide it" >&2
exit 77
