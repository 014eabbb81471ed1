#!/usr/bin/env bash
# Brings up a private single-node Slurm cluster on localhost for droplet's end-to-end test
# (tests/suite/slurm.rs), following design.md Sect. 5: its own state/spool/log/pid directory, its
# own munge socket and key, non-default ports, SLURM_CONF pointing at it; nothing in /etc is
# touched. Installs Debian's slurm-wlm and munge when missing (needs root).
#
#   ci/slurm-up.sh [DIR]      # default DIR: /tmp/droplet-slurm
#   source DIR/env            # exports SLURM_CONF (what sbatch/squeue/scontrol read)
#   ci/slurm-down.sh [DIR]    # stops the daemons it started, by their PIDs
#
# Exit 0: the node is idle and accepts jobs. Non-zero: Slurm could not be brought up; the
# reason is on stderr.
set -euo pipefail
DIR=${1:-/tmp/droplet-slurm}
say() { echo "slurm-up: $*" >&2; }

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    if [ "$(id -u)" != 0 ]; then
        say "slurm-wlm/munge are not installed and this is not root"; exit 3
    fi
    say "installing slurm-wlm and munge"
    export DEBIAN_FRONTEND=noninteractive
    (apt-get install -y -q slurm-wlm munge >/dev/null 2>&1 ||
        { apt-get update -q >/dev/null 2>&1 && apt-get install -y -q slurm-wlm munge >/dev/null 2>&1; }) ||
        { say "apt-get install slurm-wlm munge failed"; exit 3; }
fi
if [ "$(id -u)" != 0 ]; then
    say "the private cluster runs its daemons as root (SlurmUser=root); run as root"; exit 3
fi

# Stop a previous instance in the same directory first.
"$(dirname "$0")/slurm-down.sh" "$DIR" >/dev/null 2>&1 || true
rm -rf "$DIR"
mkdir -p "$DIR"/{state,spool,log,run,munge}
chown munge:munge "$DIR/munge"
chmod 755 "$DIR/munge"
dd if=/dev/urandom of="$DIR/munge/munge.key" bs=1024 count=1 status=none
chown munge:munge "$DIR/munge/munge.key"
chmod 0400 "$DIR/munge/munge.key"
SOCK="$DIR/munge/munge.socket"
runuser -u munge -- munged --socket="$SOCK" --key-file="$DIR/munge/munge.key" \
    --pid-file="$DIR/munge/munged.pid" --log-file="$DIR/munge/munged.log" \
    --seed-file="$DIR/munge/munged.seed" ||
    { say "munged did not start (see $DIR/munge/munged.log)"; exit 4; }

CPUS=$(nproc)
# Memory Slurm may hand out: the machine's, less 1 GiB for the system (jobs ask --mem).
MEM=$(( $(awk '/MemTotal/ {print int($2 / 1024)}' /proc/meminfo) - 1024 ))
cat >"$DIR/slurm.conf" <<CONF
ClusterName=droplet-ci
SlurmctldHost=$(hostname)(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SOCK
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/run/slurmctld.pid
SlurmdPidFile=$DIR/run/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
MinJobAge=600
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$CPUS RealMemory=$MEM State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
echo "export SLURM_CONF=$DIR/slurm.conf" >"$DIR/env"
export SLURM_CONF="$DIR/slurm.conf"

slurmctld -c -f "$SLURM_CONF" || { say "slurmctld did not start (see $DIR/log/slurmctld.log)"; exit 4; }
slurmd -N localhost -f "$SLURM_CONF" || { say "slurmd did not start (see $DIR/log/slurmd.log)"; exit 4; }

for _ in $(seq 1 60); do
    state=$(sinfo -h -N -o '%T' 2>/dev/null | head -1 || true)
    case "$state" in
        idle*) say "node localhost idle ($CPUS CPUs); source $DIR/env"; exit 0 ;;
    esac
    sleep 0.5
done
say "node not idle after 30 s (state '${state:-none}'; logs in $DIR/log)"
exit 5
