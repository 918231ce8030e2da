#!/usr/bin/env bash
# The farm test (ctest -L farm): a real single-node Slurm from Debian's packages — munged,
# slurmctld and slurmd configured in a temporary folder on localhost, each step bounded in time,
# all torn down after — renders a small scene through tools/farm/arbor-slurm, and the merged EXR
# must equal a local `arbor render` of the same scene pixel for pixel (idiff, threshold 0).
#   slurm_test.sh SOURCE_DIR ARBOR
set -euo pipefail
source_dir=$1
arbor=$2

if [ "$(id -u)" -ne 0 ]; then
  echo "farm test: needs root (it starts munged, slurmctld and slurmd)" >&2
  exit 1
fi
"$source_dir/tools/install-deps.sh" --farm

work=$(mktemp -d /tmp/arbor-farm.XXXXXX)
chmod 755 "$work"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  sleep 1
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  if [ "${KEEP_FARM:-}" = "" ]; then rm -rf "$work"; else echo "kept $work" >&2; fi
}
trap cleanup EXIT

fail() {
  echo "farm test: $*" >&2
  for log in "$work"/*.log "$work"/"farm jobs"/out/*.slurm/*.log; do
    [ -f "$log" ] && { echo "--- $log" >&2; tail -n 20 "$log" >&2; }
  done
  exit 1
}

# Waits up to $1 seconds for the command after it to succeed.
wait_for() {
  local limit=$1; shift
  local start=$SECONDS
  until "$@" >/dev/null 2>&1; do
    [ $((SECONDS - start)) -lt "$limit" ] || return 1
    sleep 1
  done
}

# munge: its own key, socket and files in the folder (munged refuses a root owner unless --force).
mkdir -p "$work/munge" "$work/state" "$work/spool" "$work/out"
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munged --force --foreground --key-file="$work/munge/munge.key" --socket="$work/munge/munge.socket" \
  --pid-file="$work/munge/munged.pid" --seed-file="$work/munge/munge.seed" \
  --log-file="$work/munged.log" &
pids+=($!)
wait_for 20 test -S "$work/munge/munge.socket" || fail "munged did not start"

node=$(hostname -s)
port=$((20000 + RANDOM % 20000))
cat > "$work/slurm.conf" <<EOF
ClusterName=arbortest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=2000 State=UNKNOWN
PartitionName=farmtest Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
# No cgroups: a container or chroot has no cgroup file system, and the test needs none. Slurm
# 22.05 initialises its cgroup plugin even with proctrack/linuxproc and task/none, and its
# "autodetect" fails without /sys/fs/cgroup; the v1 plugin named outright mounts nothing until a
# cgroup plugin (proctrack/cgroup, task/cgroup) asks it to, and none does here.
cat > "$work/cgroup.conf" <<EOF
CgroupPlugin=cgroup/v1
CgroupAutomount=no
EOF
export SLURM_CONF=$work/slurm.conf
slurmctld -D -f "$SLURM_CONF" > "$work/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$node" > "$work/slurmd.out" 2>&1 &
pids+=($!)
wait_for 60 bash -c "sinfo -h -N -o '%T' | grep -Eq '^(idle|mixed|allocated)'" || fail "the node did not come up"

# The scene, the parts, the scripts and the outputs in a folder whose name has a space.
job="$work/farm jobs"
mkdir -p "$job"

# A small scene: 2x2 tiles x 2 pass groups = 8 units.
cat > "$job/scene.toml" <<EOF
[render]
width = 40
height = 30
spp = 16
pass_spp = 4
[camera]
position = [0.0, -14.0, 3.0]
look_at = [0.0, 0.0, 4.0]
fov = 50.0
[[tree]]
species = "$source_dir/species/quaking_aspen.toml"
[ground]
enabled = true
EOF
submitted=$("$source_dir/tools/farm/arbor-slurm" "$job/scene.toml" --arbor "$arbor" --tiles 2x2 --pass-groups 2 \
  --seed 3 --cpus 1 --mem 500M --unit-time 10 -o "$job/out/farm.exr") || fail "arbor-slurm failed"
echo "$submitted"
units_job=$(printf '%s\n' "$submitted" | awk '/^units:/ {print $2}')
merge_job=$(printf '%s\n' "$submitted" | awk '/^merge:/ {print $2}')
[ -n "$units_job" ] && [ -n "$merge_job" ] || fail "no job ids in: $submitted"
[ "$(wc -l < "$job/out/farm.slurm/units.txt")" -eq 8 ] || fail "expected 8 units"

# Done when the merge job has left the queue (bounded); it must have written the EXR.
wait_for 300 bash -c "! squeue -h -j $units_job,$merge_job 2>/dev/null | grep -q ." || fail "the jobs did not finish in 300 s"
[ -f "$job/out/farm.exr" ] || fail "the merge job wrote no EXR"
grep -q "merged 8 parts" "$job/out/farm.slurm/merge.log" || fail "the merge log does not report 8 parts"

"$arbor" render "$job/scene.toml" --seed 3 -o "$job/out/local.exr" 2>/dev/null
idiff -q -fail 0 -failpercent 0 -warn 0 "$job/out/farm.exr" "$job/out/local.exr" ||
  fail "the farm's EXR differs from a local render"
echo "farm test: 8 units through Slurm (jobs $units_job, $merge_job), merged EXR equals the local render"

# The plan's defaults (--tiles 1x1 --pass-groups 1, docs/farm.md's advice for animations): one
# unit that is the whole render, which must keep its film state for the merge job.
submitted=$("$source_dir/tools/farm/arbor-slurm" "$job/scene.toml" --arbor "$arbor" \
  --seed 3 --cpus 1 --mem 500M --unit-time 10 -o "$job/out/one.exr") || fail "arbor-slurm (one unit) failed"
echo "$submitted"
units_job=$(printf '%s\n' "$submitted" | awk '/^units:/ {print $2}')
merge_job=$(printf '%s\n' "$submitted" | awk '/^merge:/ {print $2}')
[ "$(wc -l < "$job/out/one.slurm/units.txt")" -eq 1 ] || fail "expected 1 unit"
wait_for 300 bash -c "! squeue -h -j $units_job,$merge_job 2>/dev/null | grep -q ." || fail "the one-unit jobs did not finish in 300 s"
[ -f "$job/out/one.exr" ] || fail "the one-unit plan's merge job wrote no EXR"
grep -q "merged 1 part: .*(the whole render)" "$job/out/one.slurm/merge.log" || fail "the one-unit merge log does not report the whole render"
idiff -q -fail 0 -failpercent 0 -warn 0 "$job/out/one.exr" "$job/out/local.exr" ||
  fail "the one-unit farm EXR differs from a local render"
echo "farm test: 1 unit through Slurm (jobs $units_job, $merge_job), merged EXR equals the local render"
