#!/bin/bash
# test_slurm_cluster: the documented job array (docs/command-line.md, "Across machines") on a real
# one-node Slurm started here on loopback with its own munge, then the merge job chained with
# afterok; the merged rates.csv, rates.json and seed_outcomes.json must be byte-identical to one
# seeds run over the same range. Then the documented rerun of failed shards: a shard folder is
# lost, merge names it ("rerun shards: K"), only that shard is resubmitted, and the merge holds
# again. Skipped (exit 77) where Slurm's daemons or munge are not installed.
#   check-slurm.sh <activetouch-cli> <experiments folder>
set -u
cli=$1
experiments=$2
for tool in munged mungekey slurmctld slurmd sbatch squeue sinfo scontrol; do
    if ! command -v "$tool" > /dev/null 2>&1 && [ ! -x "/usr/sbin/$tool" ]; then
        echo "$tool not found: install slurm-wlm and munge to run this test"
        exit 77
    fi
done
export PATH="$PATH:/usr/sbin"
work=$(mktemp -d /tmp/activetouch-slurm.XXXXXX)
pids=()
cleanup() {
    for p in "${pids[@]}"; do kill "$p" 2> /dev/null; done
    sleep 0.5
    for p in "${pids[@]}"; do kill -9 "$p" 2> /dev/null; done
    rm -rf "$work"
}
trap cleanup EXIT
fail() {
    echo "FAIL: $*"
    for f in "$work"/*.log; do echo "--- $f"; tail -n 20 "$f"; done
    exit 1
}
free_port() {
    python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
# Waits up to $1 tenths of a second for the command after it to succeed.
wait_for() {
    local tenths=$1
    shift
    for _ in $(seq 1 "$tenths"); do
        "$@" > /dev/null 2>&1 && return 0
        sleep 0.1
    done
    return 1
}

# munge, with its own key and socket.
mkdir -p "$work/munge" "$work/state" "$work/spool" "$work/runs"
chmod 700 "$work/munge"
mungekey --create --keyfile="$work/munge/munge.key" > "$work/mungekey.log" 2>&1 ||
    fail "mungekey could not create a key"
munged --force --key-file="$work/munge/munge.key" --socket="$work/munge/munge.sock" \
    --pid-file="$work/munge/munged.pid" --log-file="$work/munged.log" \
    --seed-file="$work/munge/munged.seed" > "$work/munged-start.log" 2>&1 ||
    fail "munged did not start"
pids+=("$(cat "$work/munge/munged.pid")")

# A one-node cluster on loopback.
node=$(hostname -s)
cpus=$(nproc)
cat > "$work/slurm.conf" << CONF
ClusterName=activetouch-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.sock
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"
slurmctld -D -i -f "$SLURM_CONF" > "$work/slurmctld-start.log" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$node" > "$work/slurmd-start.log" 2>&1 &
pids+=($!)
idle() { sinfo -h -N -o '%t' | grep -q idle; }
wait_for 600 idle || fail "the node did not come up idle"
echo "slurm: one node ($node, $cpus CPUs) idle"

# The job array as docs/command-line.md shows it, scaled to 40 seeds in 4 shards.
cd "$work/runs" || fail "no work folder"
cat > paper_seeds.sh << JOB
#!/bin/bash
#SBATCH --job-name=paper-seeds --array=1-4 --cpus-per-task=1 --output=$work/shard_%a.log
"$cli" seeds "$experiments/paper.json" --from 1 --to 40 \\
    --shard "\${SLURM_ARRAY_TASK_ID}/4" --jobs "\${SLURM_CPUS_PER_TASK}" \\
    --out "shards/shard_\${SLURM_ARRAY_TASK_ID}" --no-figures
JOB
merge_job() {
    sbatch --parsable --dependency="afterok:$1" --output="$work/merge.log" \
        --wrap "\"$cli\" merge shards/shard_* --out merged --no-figures"
}
gone() { [ -z "$(squeue -h -j "$1" 2> /dev/null)" ]; }
array=$(sbatch --parsable paper_seeds.sh) || fail "sbatch refused the job array"
merge=$(merge_job "$array") || fail "sbatch refused the merge job"
echo "submitted the array $array and the merge $merge (afterok)"
wait_for 3000 gone "$merge" || fail "the merge job did not end"
[ -f merged/rates.csv ] || fail "the merge job wrote no merged/rates.csv"

"$cli" seeds "$experiments/paper.json" --from 1 --to 40 --out one --no-figures > "$work/one.log" 2>&1 ||
    fail "the single seeds run failed"
compare() {
    for f in rates.csv rates.json seed_outcomes.json; do
        cmp "merged/$f" "one/$f" || fail "merged/$f differs from one seeds run's"
    done
}
compare
echo "merged rates.csv, rates.json and seed_outcomes.json are byte-identical to one seeds run"

# A shard lost: merge names it, only it runs again, and the merge holds.
rm -rf shards/shard_3 merged
"$cli" merge shards/shard_* --out merged --no-figures > "$work/refused.log" 2>&1 &&
    fail "merge took three shards of four"
rerun=$(sed -n 's/^rerun shards: //p' "$work/refused.log")
[ "$rerun" = "3" ] || fail "merge named shards '$rerun' to rerun, not 3"
again=$(sbatch --parsable --array="$rerun" paper_seeds.sh) || fail "sbatch refused the rerun"
merge=$(merge_job "$again") || fail "sbatch refused the second merge"
wait_for 3000 gone "$merge" || fail "the second merge job did not end"
compare
echo "shard 3 rerun alone: the merge is byte-identical again"
exit 0
