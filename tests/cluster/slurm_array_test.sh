#!/usr/bin/env bash
# A real single-node Slurm cluster (munge, slurmctld, slurmd in the foreground, no systemd)
# runs a sweep as a job array of shards; `slambox sweep --merge` must then give a
# results.csv byte-identical to the same sweep run locally.
# Usage: slurm_array_test.sh SLAMBOX_BINARY SOURCE_DIR. Exit 77 = skipped (CTest SKIP).
# Every wait and every Slurm/munge client call is bounded (`timeout`): when a daemon cannot
# start (no cgroup file system, host name that does not resolve, munge "Unauthorized
# credential"), the test skips within 30 s with the daemon's own error line.
set -euo pipefail
STARTUP_S=${SLAMBOX_SLURM_STARTUP_S:-24}   # daemons up and node idle, or skip (+ one client call: < 30 s)
CLIENT_S=5                                  # one sinfo/squeue/sbatch/scancel call
JOB_S=120                                   # the array job itself (4 tiny runs)
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
    SLURM_CONF=$tmp/slurm.conf timeout "$CLIENT_S" scancel --quiet --user="$(id -un)" 2>/dev/null
    for _ in $(seq 1 25); do
      [ -z "$(SLURM_CONF=$tmp/slurm.conf timeout 2 squeue -h 2>/dev/null)" ] && break
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

# The daemons' own first error line (slurmd/slurmctld log "error:", munged "Error:"/"fatal").
daemon_error() {
  local line
  line=$(grep -hiE "error|fatal|unauthorized" "$tmp"/log/* 2>/dev/null | head -1 || true)
  echo "${line:-no error line in the daemon logs}"
}
skip() {
  echo "SKIP: $1: $(daemon_error)"
  for f in "$tmp"/log/*; do echo "--- $f"; tail -5 "$f"; done
  exit 77
}
deadline=$((SECONDS + STARTUP_S))

# munge with a private key and socket
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge/munge.key"
setsid munged -F --force --key-file="$tmp/munge/munge.key" --socket="$tmp/munge/munge.socket" \
  --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/log/munged.log" --seed-file="$tmp/munge/seed" \
  >"$tmp/log/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 1 50); do [ -S "$tmp/munge/munge.socket" ] && break; sleep 0.1; done
[ -S "$tmp/munge/munge.socket" ] || skip "munged did not start"
if command -v unmunge >/dev/null 2>&1; then  # a credential round trip, bounded
  timeout "$CLIENT_S" munge -n -S "$tmp/munge/munge.socket" 2>>"$tmp/log/munge.err" |
    timeout "$CLIENT_S" unmunge -S "$tmp/munge/munge.socket" >/dev/null 2>>"$tmp/log/munge.err" ||
    skip "munge cannot encode/decode a credential"
fi

host=$(hostname -s)
timeout "$CLIENT_S" getent hosts "$host" >/dev/null || skip "host name $host does not resolve (slurmd needs it)"
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
while [ "$SECONDS" -lt "$deadline" ]; do
  if timeout "$CLIENT_S" sinfo -h -o "%T" 2>>"$tmp/log/sinfo.err" | grep -qE "idle|mixed"; then up=1; break; fi
  for p in "${pids[@]}"; do kill -0 "$p" 2>/dev/null || skip "a daemon exited at start-up"; done
  sleep 0.2
done
[ -n "$up" ] || skip "slurmctld/slurmd did not bring the node up within ${STARTUP_S} s"

# The sweep: small and fast, 2 shards.
cat >"$tmp/sweep.yaml" <<YAML
scenarios: [landmarks]
algorithms: [odometry]
seeds: 4
set: {duration_s: 15}
YAML
"$slambox" sweep "$tmp/sweep.yaml" -o "$tmp/out" --emit-slurm --shards 2 --cpus-per-task 1 --time 00:10:00 >"$tmp/job.sh"
grep -q -- "--array=0-1" "$tmp/job.sh"
jobid=$(timeout "$CLIENT_S" sbatch --parsable "$tmp/job.sh" 2>>"$tmp/log/sbatch.err") ||
  skip "sbatch did not accept the job (exit $?)"
echo "submitted array job $jobid"
job_deadline=$((SECONDS + JOB_S))
queued() { [ -n "$(timeout "$CLIENT_S" squeue -h -j "$jobid" 2>/dev/null)" ]; }
while [ "$SECONDS" -lt "$job_deadline" ] && queued; do sleep 0.2; done
! queued || { echo "FAIL: array job still queued/running after $JOB_S s: $(daemon_error)"; exit 1; }
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
