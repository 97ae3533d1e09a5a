#!/usr/bin/env bash
# Many machines through an existing scheduler (issue #40): a single-node Slurm cluster (munged,
# slurmctld, slurmd, all in a temporary folder on free ports) runs `penumbra-render --batch
# --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT` as a job array over a small job file;
# every output is written, each task writes its own results file, and rerunning one task of
# the array skips what it finished. docs/pipelines.md shows the same job for a real cluster.
# Skipped (exit 77) where Slurm is not installed (`tools/setup --slurm` installs it) or the
# test is not root (slurmd runs the jobs).
# Usage: slurm_array.sh <dir of libpenumbra.a> <build dir>
set -uo pipefail

TOOL="$2/tools/render/penumbra-render"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
A="$ROOT/assets"
for p in slurmctld slurmd sbatch sinfo munged mungekey; do
  if ! command -v "$p" >/dev/null && [ ! -x "/usr/sbin/$p" ]; then
    echo "SKIP: $p is not installed (tools/setup --slurm installs Slurm and MUNGE)"
    exit 77
  fi
done
if [ "$(id -u)" != 0 ]; then
  echo "SKIP: the single-node cluster needs root (slurmd launches the tasks)"
  exit 77
fi
[ -x "$TOOL" ] || { echo "FAIL: $TOOL not built"; exit 1; }
export PATH="$PATH:/usr/sbin"
D="$(mktemp -d)"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
stop() {
  for f in ctld.pid d.pid munged.pid; do
    [ -f "$D/$f" ] && kill "$(cat "$D/$f")" 2>/dev/null
  done
  sleep 1
  rm -rf "$D"
}
trap stop EXIT
mkdir -p "$D/state" "$D/spool" "$D/out"

ports=$(python3 -c 'import socket
ss=[socket.socket() for _ in range(2)]
[s.bind(("127.0.0.1", 0)) for s in ss]
print(" ".join(str(s.getsockname()[1]) for s in ss))')
read -r ctld_port d_port <<<"$ports"
host=$(hostname -s)

mungekey --create --keyfile "$D/munge.key" >/dev/null 2>&1 || { fail "mungekey"; exit 1; }
chmod 600 "$D/munge.key"
munged --key-file="$D/munge.key" --socket="$D/munge.sock" --pid-file="$D/munged.pid" \
  --log-file="$D/munged.log" --seed-file="$D/munge.seed" --force || { fail "munged did not start"; exit 1; }

cat >"$D/slurm.conf" <<EOF
ClusterName=penumbratest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$D/munge.sock
CredType=cred/munge
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/ctld.pid
SlurmdPidFile=$D/d.pid
SlurmctldLogFile=$D/ctld.log
SlurmdLogFile=$D/d.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$D/slurm.conf"
slurmctld -f "$SLURM_CONF" -i || { fail "slurmctld did not start: $(tail -n 3 "$D/ctld.log")"; exit 1; }
slurmd -f "$SLURM_CONF" || { fail "slurmd did not start: $(tail -n 3 "$D/d.log")"; exit 1; }
for _ in $(seq 50); do
  sinfo -h -o %t 2>/dev/null | grep -q idle && break
  sleep 0.2
done
sinfo -h -o %t | grep -q idle || { fail "the node never became idle: $(sinfo 2>&1)"; exit 1; }
echo "ok: single-node Slurm up ($(sinfo -h -o '%P %D %t'))"

# Five jobs, three array tasks: tasks 0 and 1 render two each, task 2 one.
JOBS="$D/jobs.jsonl"
for s in cornell_box/cornell_box.json material_grid/material_grid.json glass/glass.json \
         product/product.json cornell_box/cornell_box.gltf; do
  name=$(basename "$s" | tr . _)
  echo "{\"scene\": \"$A/$s\", \"output\": \"$D/out/$name.png\", \"size\": \"48x32\", \"frames\": 4}"
done >"$JOBS"
# Submits the array and waits for it (polling squeue: sbatch --wait polls every few seconds).
submit() {
  local id
  id=$(sbatch --parsable --array=0-2 --output="$D/$1-%a.out" --wrap \
    "$TOOL --batch $JOBS --shard \$SLURM_ARRAY_TASK_ID/\$SLURM_ARRAY_TASK_COUNT -q") || return 1
  for _ in $(seq 600); do
    [ -z "$(squeue -h -j "${id%%;*}" 2>/dev/null)" ] && return 0
    sleep 0.2
  done
  echo "the array did not finish in 120 s"
  return 1
}
if ! submit task; then
  fail "the array failed: $(cat "$D"/task-*.out 2>/dev/null)"
fi
[ "$(ls "$D/out" | wc -l)" = 5 ] || fail "outputs: $(ls "$D/out" | tr '\n' ' ')"
for i in 0 1 2; do
  r="$D/jobs.results.$i-of-3.jsonl"
  [ -f "$r" ] || { fail "no results file for task $i"; continue; }
  want=$([ "$i" = 2 ] && echo 1 || echo 2)
  [ "$(grep -c '"status":"ok"' "$r")" = "$want" ] || fail "task $i: $(cat "$r")"
done
echo "ok: array 0-2 rendered $(ls "$D/out" | wc -l) images, results per task"

# The same array again after one image was lost (a node's disk, say): only that job renders.
rm "$D/out/glass_json.png"
submit retry || fail "the rerun failed"
[ -f "$D/out/glass_json.png" ] || fail "the rerun did not render the missing image"
[ "$(grep -c '"status":"skipped"' "$D/jobs.results.0-of-3.jsonl" "$D/jobs.results.1-of-3.jsonl" \
      "$D/jobs.results.2-of-3.jsonl" | awk -F: '{s+=$2} END{print s}')" = 4 ] ||
  fail "the rerun did not skip the four finished jobs"
echo "ok: rerun rendered only the missing image"

if [ "$failures" != 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all Slurm array checks passed"
