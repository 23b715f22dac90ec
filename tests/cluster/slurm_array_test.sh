#!/usr/bin/env bash
# A real single-node Slurm cluster (munge, slurmctld, slurmd in the foreground, no systemd)
# runs a sweep as a job array of shards; `slambox sweep --merge` must then give a
# results.csv byte-identical to the same sweep run locally.
# Usage: slurm_array_test.sh SLAMBOX_BINARY SOURCE_DIR. Exit 77 = skipped (CTest SKIP).
set -euo pipefail
slambox=$1
src=$2
for tool in munged slurmctld slurmd sbatch squeue sinfo scancel; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "SKIP: $tool not found; install slurmctld slurmd slurm-client munge (scripts/setup.sh --with-slurm)"
    exit 77
  fi
done

tmp=$(mktemp -d /tmp/slambox-slurm.XXXXXX)
chmod 711 "$tmp"
mkdir -p "$tmp/munge" "$tmp/state" "$tmp/spool" "$tmp/log"
chmod 711 "$tmp/munge"
pids=()
cleanup() {
  set +e
  if [ -f "$tmp/slurm.conf" ]; then
    SLURM_CONF=$tmp/slurm.conf scancel --quiet --user="$(id -un)" 2>/dev/null
    for _ in $(seq 1 50); do
      [ -z "$(SLURM_CONF=$tmp/slurm.conf squeue -h 2>/dev/null)" ] && break
      sleep 0.2
    done
  fi
  # stop slurmd, slurmctld, munged in that order (pids were stored in start order)
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
    kill "${pids[i]}" 2>/dev/null
    for _ in $(seq 1 50); do kill -0 "${pids[i]}" 2>/dev/null || break; sleep 0.1; done
    kill -9 "${pids[i]}" 2>/dev/null
  done
  rm -rf "$tmp"
}
trap cleanup EXIT

skip() { echo "SKIP: $1"; for f in "$tmp"/log/*; do echo "--- $f"; tail -5 "$f"; done; exit 77; }

# munge with a private key and socket
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge/munge.key"
setsid munged -F --force --key-file="$tmp/munge/munge.key" --socket="$tmp/munge/munge.socket" \
  --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/log/munged.log" --seed-file="$tmp/munge/seed" \
  >"$tmp/log/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 1 50); do [ -S "$tmp/munge/munge.socket" ] && break; sleep 0.1; done
[ -S "$tmp/munge/munge.socket" ] || skip "munged did not start"

host=$(hostname -s)
port=$((20000 + RANDOM % 20000))
cat >"$tmp/slurm.conf" <<CONF
ClusterName=slambox
SlurmctldHost=$host
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/munge.socket
SlurmUser=$(id -un)
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SchedulerParameters=batch_sched_delay=0
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
setsid slurmctld -D -f "$SLURM_CONF" >"$tmp/log/slurmctld.out" 2>&1 &
pids+=($!)
setsid slurmd -D -f "$SLURM_CONF" >"$tmp/log/slurmd.out" 2>&1 &
pids+=($!)
up=""
for _ in $(seq 1 100); do
  if sinfo -h -o "%T" 2>/dev/null | grep -qE "idle|mixed"; then up=1; break; fi
  sleep 0.2
done
[ -n "$up" ] || skip "slurmctld/slurmd did not bring the node up"

# The sweep: small and fast, 2 shards.
cat >"$tmp/sweep.yaml" <<YAML
scenarios: [landmarks]
algorithms: [odometry]
seeds: 4
set: {duration_s: 15}
YAML
"$slambox" sweep "$tmp/sweep.yaml" -o "$tmp/out" --emit-slurm --shards 2 --cpus-per-task 1 --time 00:10:00 >"$tmp/job.sh"
grep -q -- "--array=0-1" "$tmp/job.sh"
jobid=$(sbatch --parsable "$tmp/job.sh")
echo "submitted array job $jobid"
for _ in $(seq 1 600); do
  [ -z "$(squeue -h -j "$jobid" 2>/dev/null)" ] && break
  sleep 0.2
done
[ -z "$(squeue -h -j "$jobid" 2>/dev/null)" ] || { echo "FAIL: array job still queued/running after 120 s"; exit 1; }
ls "$tmp/out/slurm"
"$slambox" sweep --merge "$tmp/out" --no-figures
"$slambox" sweep "$tmp/sweep.yaml" -o "$tmp/local" -j 2 --no-figures
if ! cmp "$tmp/out/results.csv" "$tmp/local/results.csv"; then
  echo "FAIL: results.csv from the Slurm array differs from the local sweep"
  diff "$tmp/out/results.csv" "$tmp/local/results.csv" | head
  exit 1
fi
rows=$(($(wc -l <"$tmp/out/results.csv") - 1))
[ "$rows" -eq 4 ] || { echo "FAIL: expected 4 result rows, got $rows"; exit 1; }
echo "PASS: Slurm job array of 2 shards gave the same $rows rows as the local sweep"
