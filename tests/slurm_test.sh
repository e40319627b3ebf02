#!/usr/bin/env bash
# A sweep as a Slurm job array, for real: start a single-node Slurm (munge, slurmctld, slurmd from Debian's
# packages) on localhost, submit cluster/sweep.sbatch as an array of 3 shards, wait, merge, and compare the
# merged sweep.csv with the unsplit run, byte for byte. Everything runs under a temporary directory, on ports
# of its own, and is stopped at exit.
# usage: slurm_test.sh path/to/gonio   (run from the repository root)
set -u
PATH="$PATH:/usr/sbin:/sbin"   # munged and the Slurm daemons live in sbin
gonio="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
for tool in munged slurmctld slurmd sbatch squeue sinfo; do
    command -v "$tool" >/dev/null || { echo "FAIL: $tool not found (./run installs munge, slurmctld, slurmd, slurm-client)"; exit 1; }
done
d="$(mktemp -d)"
pids=()
cleanup() {
    for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
    [ -f "$d/munged.pid" ] && kill "$(cat "$d/munged.pid")" 2>/dev/null
    sleep 0.5
    rm -rf "$d"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; for f in "$d"/log/*; do echo "--- $f"; tail -20 "$f"; done; exit 1; }
mkdir -p "$d/state" "$d/spool" "$d/log" "$d/munge"
user="$(id -un)"
host="$(hostname -s)"
port=$((20000 + ($$ % 5000) * 2))
# munge with a key of its own
head -c 1024 /dev/urandom > "$d/munge/munge.key"
chmod 600 "$d/munge/munge.key"
force=""; [ "$(id -u)" = 0 ] && force="--force"
munged $force --key-file="$d/munge/munge.key" --socket="$d/munge/munge.socket" --pid-file="$d/munged.pid" \
       --log-file="$d/log/munged.log" --seed-file="$d/munge/seed" || fail "munged did not start"
cat > "$d/slurm.conf" <<EOC
ClusterName=gonio-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$d/munge/munge.socket
SlurmUser=$user
SlurmdUser=$user
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/log/slurmctld.log
SlurmdLogFile=$d/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOC
export SLURM_CONF="$d/slurm.conf"
slurmctld -D -f "$SLURM_CONF" > "$d/log/slurmctld.out" 2>&1 & pids+=($!)
sleep 1
slurmd -D -f "$SLURM_CONF" > "$d/log/slurmd.out" 2>&1 & pids+=($!)
for _ in $(seq 60); do sinfo -h -o %t 2>/dev/null | grep -q idle && break; sleep 0.5; done
sinfo -h -o %t | grep -q idle || fail "the Slurm node did not come up"
# the sweep, as an array of 3 shards
job=$(GONIO="$gonio" sbatch --parsable --array=1-3 --output="$d/log/task-%a.log" cluster/sweep.sbatch \
      tests/sweeps/tiny.toml "$d/array") || fail "sbatch refused the job"
for _ in $(seq 300); do [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break; sleep 0.5; done
[ -z "$(squeue -h -j "$job" 2>/dev/null)" ] || fail "the array job did not finish in 150 s"
for t in 1 2 3; do grep -q "shard $t/3" "$d/log/task-$t.log" || fail "array task $t did not run its shard"; done
"$gonio" merge "$d/array" > /dev/null || fail "merge of the array's shards failed"
"$gonio" sweep tests/sweeps/tiny.toml --quiet --out "$d/unsplit" > /dev/null || fail "the unsplit sweep failed"
cmp -s "$d/array/sweep.csv" "$d/unsplit/sweep.csv" || fail "the Slurm array's merged sweep.csv differs from the unsplit run"
echo "slurm: a 3-task job array on a local Slurm merged to the unsplit sweep.csv, byte for byte"
