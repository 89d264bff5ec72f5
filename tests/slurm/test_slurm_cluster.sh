#!/usr/bin/env bash
# A sharded sweep on a real, throwaway one-node Slurm cluster: munged, slurmctld and slurmd are
# started in a temporary folder (no systemd, nothing in /etc), scripts/slurm/submit.sh submits
# a 3-task job array and the merge that depends on it, and the merged rows must equal a
# single-process run of the same config in every error column (relieflab compare with zero
# tolerances; renders on llvmpipe are deterministic). The daemons are stopped by their PIDs
# on every exit. Needs the packages of scripts/install-deps.sh.
#   tests/slurm/test_slurm_cluster.sh RELIEFLAB REPO_ROOT
set -euo pipefail
relieflab=$(realpath "$1") root=$(realpath "$2")
for tool in mungekey munged slurmctld slurmd sbatch sinfo squeue; do
  command -v "$tool" > /dev/null || { echo "FAIL: $tool missing; run scripts/install-deps.sh"; exit 1; }
done
dir=$(mktemp -d /tmp/relieflab-slurm.XXXXXX)
chmod 755 "$dir"
mkdir -p "$dir/state" "$dir/spool"
stop() {
  local status=$?
  for d in slurmd slurmctld munged; do
    [ -f "$dir/$d.pid" ] && kill "$(cat "$dir/$d.pid")" 2> /dev/null || true
  done
  sleep 2
  # slurmd ignores SIGTERM while it cannot reach the controller.
  for d in slurmd slurmctld munged; do
    [ -f "$dir/$d.pid" ] && kill -9 "$(cat "$dir/$d.pid")" 2> /dev/null || true
  done
  if [ "$status" -ne 0 ]; then
    echo "--- logs (kept in $dir)"
    tail -n 20 "$dir"/*.log "$dir"/cluster/logs/*.log 2> /dev/null || true
  else
    rm -rf "$dir"
  fi
}
trap stop EXIT

# Two free ports (nothing listening), so that clusters of parallel runs do not meet.
port_free() { ! (exec 3<> "/dev/tcp/127.0.0.1/$1") 2> /dev/null; }
ports=()
for ((p = 20000 + RANDOM % 20000; ${#ports[@]} < 2; ++p)); do port_free "$p" && ports+=("$p"); done

mungekey -c -k "$dir/munge.key" > /dev/null
munged -F -S "$dir/munge.sock" --key-file="$dir/munge.key" --pid-file="$dir/munged.pid" \
  --seed-file="$dir/seed" > "$dir/munged.log" 2>&1 &
cat > "$dir/slurm.conf" << CONF
ClusterName=relieflab-test
SlurmctldHost=localhost
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
AuthType=auth/munge
AuthInfo=socket=$dir/munge.sock
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerParameters=sched_interval=1
MinJobAge=4
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
NodeName=localhost CPUs=2 State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
for ((i = 0; i < 50; ++i)); do [ -S "$dir/munge.sock" ] && break; sleep 0.1; done
slurmctld -D -c -f "$SLURM_CONF" > "$dir/slurmctld.out" 2>&1 &
slurmd -D -N localhost -f "$SLURM_CONF" > "$dir/slurmd.out" 2>&1 &
for ((i = 0; i < 60; ++i)); do
  timeout 5 sinfo -h -o %t 2> /dev/null | grep -q idle && break
  sleep 0.5
done
timeout 5 sinfo -h -o %t | grep -q idle || { echo "FAIL: the node never came up"; exit 1; }

# The sharding tests' small sweep: procedural scenes, normal and relief, 4 views, 64^2.
cp "$root/tests/shard_sweep.toml" "$dir/sweep.toml"

start=$(date +%s%N)
timeout 400 "$root/scripts/slurm/submit.sh" --wait "$dir/sweep.toml" "$dir/cluster" 3 "$relieflab" \
  -- --cpus-per-task=1
sharded_ms=$((($(date +%s%N) - start) / 1000000))
start=$(date +%s%N)
"$relieflab" run "$dir/sweep.toml" --out "$dir/single" -q
single_ms=$((($(date +%s%N) - start) / 1000000))

# Every default metric with zero tolerance: any difference is a regression.
{
  echo "[tolerances]"
  for m in wrong_pct missed_pct false_pct artifact_pct shadow_disagree_pct object_disagree_pct \
    pos_err_rmse pos_err_p99 pos_err_texels_mean normal_err_mean_deg ao_err_mean fetches_mean; do
    echo "$m = { abs = 0, rel = 0 }"
  done
  echo "psnr_db = { abs = 0, rel = 0, lower_is_better = false }"
  echo "ssim = { abs = 0, rel = 0, lower_is_better = false }"
} > "$dir/exact.toml"
report=$("$relieflab" compare "$dir/single" "$dir/cluster/merged" --tolerances "$dir/exact.toml")
echo "$report" | tail -n 1
cells=$(($(wc -l < "$dir/single/rows.csv") - 1))
echo "$report" | tail -n 1 | grep -q "^$cells cells matched ($cells by key, 0 by identity): 0 worse, 0 better, 0 only in base, 0 only in new -> ok" \
  || { echo "FAIL: the merged shards differ from the single-process run"; echo "$report"; exit 1; }
[ "$(wc -l < "$dir/cluster/merged/rows.csv")" = "$(wc -l < "$dir/single/rows.csv")" ] \
  || { echo "FAIL: rows.csv line counts differ"; exit 1; }
for i in 0 1 2; do grep -q "shard $i/3" "$dir/cluster/shard-$i/run.log" || { echo "FAIL: shard $i"; exit 1; }; done
echo "PASS: 3 Slurm shards of $cells cells merged equal the single-process run" \
  "(sharded ${sharded_ms} ms incl. scheduling and merge, single process ${single_ms} ms)"
