#!/usr/bin/env bash
# docs/batch.md's cluster section run for real: a single-node Slurm 22.05 (Debian's slurm-wlm, with
# munge) started as processes this script owns, configured for this machine's cores and memory, its
# state in a temporary folder. Its shards.sh and merge.sh are submitted as written over a manifest
# of 24 pairs with 4 array tasks and a dependent merge; then a task is cancelled mid-run with
# scancel and submitted again; then GNU parallel's line; then one pair's samples in 4 shards
# (pair-shards.sh, pair-merge.sh), merged to one process's report, also with a shard cancelled. Each time: every pair's report present
# once, every task's exit code 0, and summary.csv equal to a one-process `roving batch` of the same
# manifest (timings aside). Every daemon is stopped by pid and the state removed, also on failure.
# As root; needs the build (scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/step.sh
source_dir="$PWD"
bash scripts/setup.sh slurm
[ -x build/roving/roving ] || { echo "test-slurm: build/roving/roving is missing: run scripts/build.sh" >&2; exit 1; }

work="$(mktemp -d /tmp/roving-slurm.XXXXXX)"
pids=()
stop() {
  set +e
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null; done
  [ -f "$work/munge/munged.pid" ] && kill "$(cat "$work/munge/munged.pid")" 2>/dev/null
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null; done
  rm -rf "$work"
}
trap stop EXIT
fail() {
  echo "test-slurm: $*" >&2
  for log in "$work"/log/*.log; do echo "--- $log (last lines)" >&2; tail -n 15 "$log" >&2; done
  exit 1
}

# `roving` on PATH, as the scripts call it.
mkdir -p "$work/bin" "$work/munge" "$work/state" "$work/spool" "$work/log"
ln -s "$source_dir/build/roving/roving" "$work/bin/roving"
export PATH="$work/bin:$PATH"

# munge: a fresh key, a socket of our own.
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munged --force --socket="$work/munge/socket" --key-file="$work/munge/munge.key" --log-file="$work/log/munged.log" \
  --pid-file="$work/munge/munged.pid" --seed-file="$work/munge/seed"

# Slurm: this machine as the one node, its cores and memory (less 1 GiB for the system); ports
# above the usual ones, so a real Slurm on the machine is left alone.
export SLURM_CONF="$work/slurm.conf"
cat > "$SLURM_CONF" <<CONF
ClusterName=roving-test
SlurmctldHost=$(hostname -s)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
MpiDefault=none
MinJobAge=3600
KillWait=10
NodeName=$(hostname -s) CPUs=$(nproc) RealMemory=$(( $(free -m | awk '/^Mem:/ {print $2}') - 1024 )) State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=60 State=UP
CONF
slurmctld -D -f "$SLURM_CONF" > "$work/log/slurmctld-stdout.log" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" > "$work/log/slurmd-stdout.log" 2>&1 &
pids+=($!)
for i in $(seq 60); do
  sinfo -h -o %t 2>/dev/null | grep -q idle && break
  [ "$i" = 60 ] && fail "the node did not come up within 30 s"
  sleep 0.5
done
echo "test-slurm: $(sinfo -h -o '%P %D node(s) %c cores %m MB, %t') (Slurm $(sinfo -V | cut -d' ' -f2))"

# Waits until none of the jobs named is pending or running (at most $2 seconds).
wait_jobs() {
  for i in $(seq $(( $2 * 2 ))); do
    [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0
    sleep 0.5
  done
  squeue >&2
  fail "jobs $1 still queued or running after $2 s"
}
# Every task of job $1 ended COMPLETED with exit code 0 ($2 tasks).
check_exit_codes() {
  local states
  states=$(scontrol -o show job "$1" | grep -o 'JobState=[A-Z]* .* ExitCode=[0-9:]*' | sed 's/JobState=\([A-Z]*\) .*ExitCode=\([0-9:]*\)/\1 \2/' | sort | uniq -c)
  [ "$(echo "$states" | awk '$2 == "COMPLETED" && $3 == "0:0" {n += $1} END {print n + 0}')" = "$2" ] ||
    fail "job $1: expected $2 tasks COMPLETED with exit code 0:0, found: $states"
}
# Cancels task 1 of array job $1 once it has run $2 seconds.
cancel_task_1() {
  for i in $(seq 240); do
    [ -n "$(squeue -h -t R -j "${1}_1" 2>/dev/null)" ] && break
    sleep 0.5
  done
  sleep "$2"
  scancel "${1}_1"
}
# The summary without its seconds column.
summary() {
  /usr/bin/python3 -c '
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
drop = rows[0].index("seconds")
for row in rows: print(",".join(v for i, v in enumerate(row) if i != drop))' "$1/summary.csv"
}
# Every pair 0..N-1 has exactly one report in folder $1, no temporary file is left, and its
# summary equals the one-process run's in $2.
check_folder() {
  /usr/bin/python3 - "$1" "$3" <<'PY' || fail "$1: reports are not one per pair"
import json, os, sys
folder, count = sys.argv[1], int(sys.argv[2])
names = os.listdir(folder)
assert not [n for n in names if n.startswith(".")], f"temporary files left: {names}"
indexes = sorted(json.load(open(os.path.join(folder, n)))["batch"]["index"] for n in names if n.endswith(".json"))
assert indexes == list(range(count)), f"report indexes {indexes}"
PY
  [ "$(summary "$1")" = "$(summary "$2")" ] || { diff <(summary "$1") <(summary "$2") >&2; fail "$1/summary.csv differs from the one-process run's"; }
}

# 24 pairs: the bunny against its derived models, by three exact methods and closest point.
step "the models (roving-datasets --quick)" sh -c "./build/datasets_gen/roving-datasets --out '$work/models' --quick >/dev/null 2>&1"
tests=($(cd "$work/models" && ls bunny-*.ply bunny-*.binvox | head -n 6))
methods=(embree cgal v2p-aabb embree)
make_manifest() {  # $1: the file, $2: extra column value for samples
  echo "reference,test,method,semantics,samples" > "$1"
  for k in $(seq 0 23); do
    method=${methods[$((k / 6))]}
    semantics=first-hit
    [ "$method" = v2p-aabb ] || [ "$k" -ge 18 ] && semantics=closest
    echo "$work/models/bunny.ply,$work/models/${tests[$((k % 6))]},$method,$semantics,$2" >> "$1"
  done
}
mkdir -p "$work/run1" "$work/run2" "$work/run3"
make_manifest "$work/pairs.csv" faces
make_manifest "$work/slow-pairs.csv" area:400000
block() { /usr/bin/python3 "$source_dir/scripts/docs_blocks.py" "$source_dir/docs/batch.md" "$@"; }
for run in run1 run2; do
  block bash 0 > "$work/$run/shards.sh"
  block bash 1 > "$work/$run/merge.sh"
done
cp "$work/pairs.csv" "$work/run1/pairs.csv"
cp "$work/slow-pairs.csv" "$work/run2/pairs.csv"
cp "$work/pairs.csv" "$work/run3/pairs.csv"
step "the same manifests in one process (the expected summaries)" sh -c \
  "roving batch '$work/pairs.csv' --out '$work/single' --quiet >/dev/null && roving batch '$work/slow-pairs.csv' --out '$work/single-slow' --quiet >/dev/null"

# 1. The array and the dependent merge, as docs/batch.md submits them.
cd "$work/run1"
eval "$(block sh 0)" > merge.id
merge_id=$(cat merge.id)
step "4 array tasks and the merge (jobs $jobid, $merge_id)" wait_jobs "$jobid,$merge_id" 300
check_exit_codes "$jobid" 4
check_exit_codes "$merge_id" 1
check_folder "$work/run1/results" "$work/single" 24
echo "test-slurm: array of 4 shards + merge: 24 reports, exit codes 0, summary.csv equal to one process's"

# 2. A task cancelled mid-run, then submitted again: the set completes without duplicates.
cd "$work/run2"
jobid=$(sbatch --parsable --array=0-3 shards.sh)
cancel_task_1 "$jobid" 1.5
step "the array with task 1 cancelled (job $jobid)" wait_jobs "$jobid" 300
scontrol -o show job "$jobid" | grep 'ArrayTaskId=1 ' | grep -q 'JobState=CANCELLED' ||
  fail "task 1 of job $jobid was not cancelled: $(scontrol -o show job "$jobid" | grep -o 'ArrayTaskId=[0-9-]* .*JobState=[A-Z]*' )"
before=$(ls results/*.json | wc -l)
again=$(sbatch --parsable --array=1 --export=ALL,SHARDS=4 shards.sh)
merge_id=$(sbatch --parsable --dependency=afterany:$again merge.sh)
step "task 1 again and the merge (jobs $again, $merge_id)" wait_jobs "$again,$merge_id" 300
check_exit_codes "$again" 1
check_folder "$work/run2/results" "$work/single-slow" 24
echo "test-slurm: task 1 cancelled after $before reports, resubmitted: 24 reports once each, summary.csv equal to one process's"

# 3. GNU parallel's line, as written.
cd "$work/run3"
step "GNU parallel's line" bash -c "$(block sh 1)" >/dev/null
check_folder "$work/run3/results" "$work/single" 24
echo "test-slurm: GNU parallel's 8 shards + merge: summary.csv equal to one process's"

# 4. One pair in 4 shards and the merge (pair-shards.sh, pair-merge.sh), equal to one process's
# report; then again with task 1 cancelled mid-run: no part from it, a merge naming it missing,
# and once it is resubmitted alone, the same report.
# $1, $2: reports equal but for times and how they ran; their certified Hausdorff intervals (each
# shard bounds its own triangles) overlap, each no wider than asked.
same_report() {
  /usr/bin/python3 - "$1" "$2" <<'PY' || fail "$2 differs from the one-process report $1"
import json, sys
incidental = {"seconds", "command_line", "tool", "merged_from", "hausdorff_certified"}
def strip(x):
    if isinstance(x, dict): return {k: strip(v) for k, v in x.items() if k not in incidental}
    if isinstance(x, list): return [strip(v) for v in x]
    return x
reports = [json.load(open(p)) for p in sys.argv[1:]]
one, merged = (strip(r) for r in reports)
assert one == merged, [k for k in one if one[k] != merged.get(k)]
a, b = (r["hausdorff_certified"] for r in reports)
assert a["lower"] <= b["upper"] and b["lower"] <= a["upper"], (a, b)
assert max(h["upper"] - h["lower"] for h in (a, b)) <= a["bound"], (a, b)
PY
}
mkdir -p "$work/run4" && cd "$work/run4"
ln -s "$work/models/bunny.ply" ref.ply
ln -s "$work/models/${tests[0]}" test.ply
block bash 2 > pair-shards.sh
block bash 3 > pair-merge.sh
export SAMPLES=area:20000000
step "one pair in one process ($SAMPLES)" sh -c \
  "roving measure ref.ply test.ply --samples $SAMPLES --semantics closest --json one.json --quiet >/dev/null"
jobid=$(sbatch --parsable --array=0-3 pair-shards.sh)
merge_id=$(sbatch --parsable --mem=1G --dependency=afterok:$jobid pair-merge.sh)
step "one pair in 4 shards and the merge (jobs $jobid, $merge_id)" wait_jobs "$jobid,$merge_id" 300
check_exit_codes "$jobid" 4
check_exit_codes "$merge_id" 1
same_report one.json report.json
echo "test-slurm: one pair in 4 shards + merge: the one-process report"
rm -rf parts report.json
jobid=$(sbatch --parsable --array=0-3 pair-shards.sh)
cancel_task_1 "$jobid" 1
step "the pair's shards with task 1 cancelled (job $jobid)" wait_jobs "$jobid" 300
[ ! -e parts/1.part ] || fail "the cancelled shard 1 left a part"
[ -z "$(ls -A parts | grep '^\.')" ] || fail "temporary files left in parts/: $(ls -A parts)"
roving merge parts/*.part --json report.json 2> merge.err && fail "the merge of 3 parts of 4 succeeded"
grep -q "shard 1/4 missing" merge.err || fail "the merge did not name the missing shard: $(cat merge.err)"
[ ! -e report.json ] || fail "a failed merge wrote report.json"
again=$(sbatch --parsable --array=1 --export=ALL,SHARDS=4 pair-shards.sh)
merge_id=$(sbatch --parsable --mem=1G --dependency=afterok:$again pair-merge.sh)
step "shard 1 again and the merge (jobs $again, $merge_id)" wait_jobs "$again,$merge_id" 300
check_exit_codes "$merge_id" 1
same_report one.json report.json
echo "test-slurm: shard 1 cancelled, resubmitted alone, merged: the one-process report"
