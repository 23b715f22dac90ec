#!/usr/bin/env bash
# Whole-process timings of the slambox executable, from outside (start-up included), as a
# new user sees them: median of N runs of `slambox scenarios` (wall, peak RSS) and of
# `slambox simulate loop -o FILE` (wall, real-time factor = simulated duration / wall).
# Usage: bash bench/startup.sh [SLAMBOX] [N]     (default ./build/app/slambox, 7)
set -euo pipefail
exe=${1:-./build/app/slambox}
n=${2:-7}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/slambox_startup.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

median() { sort -g | awk '{v[NR]=$1} END {print (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'; }
wall_ms() {  # wall time of one run, in ms
  local t0 t1
  t0=$(date +%s%N)
  "$exe" "$@" >/dev/null 2>&1
  t1=$(date +%s%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.2f\n", (b - a) / 1e6}'
}
# Peak RSS (MiB) and CPU time (user + system, ms) of one run: CPU time is what a loaded
# machine changes least (wall time includes waiting for a core).
rss_cpu() { /usr/bin/time -f "%M %U %S" -o "$tmp/rss" "$exe" "$@" >/dev/null 2>&1; awk '{printf "%.1f %.0f\n", $1 / 1024, ($2 + $3) * 1000}' "$tmp/rss"; }

"$exe" simulate loop -o "$tmp/loop.stream" >/dev/null 2>&1  # warm the page cache
duration_s=$("$exe" run "$tmp/loop.stream" --algo odometry --no-figures -q -o "$tmp/run" >/dev/null &&
  sed -n 's/.*"duration_s": *\([0-9.eE+-]*\).*/\1/p' "$tmp/run/metrics.json" | head -1)
for i in $(seq "$n"); do wall_ms scenarios; done >"$tmp/scen_wall"
for i in $(seq "$n"); do rss_cpu scenarios; done >"$tmp/scen_rss"
for i in $(seq "$n"); do wall_ms simulate loop -o "$tmp/loop.stream"; done >"$tmp/sim_wall"
for i in $(seq "$n"); do rss_cpu simulate loop -o "$tmp/loop.stream"; done >"$tmp/sim_rss"
sim_ms=$(median <"$tmp/sim_wall")
sim_cpu=$(cut -d' ' -f2 "$tmp/sim_rss" | median)
factor() { awk -v d="$duration_s" -v w="$1" 'BEGIN {printf "%.0f", d * 1000 / w}'; }
echo "slambox scenarios:     median $(median <"$tmp/scen_wall") ms wall, $(cut -d' ' -f2 "$tmp/scen_rss" | median) ms CPU," \
  "$(cut -d' ' -f1 "$tmp/scen_rss" | median) MiB peak RSS ($n runs)"
echo "slambox simulate loop: median $sim_ms ms wall, $sim_cpu ms CPU, $(cut -d' ' -f1 "$tmp/sim_rss" | median) MiB peak RSS;" \
  "${duration_s} s simulated: $(factor "$sim_ms")x real time (wall), $(factor "$sim_cpu")x per CPU second ($n runs)"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
