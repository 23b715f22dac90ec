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
rss_mib() { /usr/bin/time -f %M -o "$tmp/rss" "$exe" "$@" >/dev/null 2>&1; awk '{printf "%.1f\n", $1 / 1024}' "$tmp/rss"; }

"$exe" simulate loop -o "$tmp/loop.stream" >/dev/null  # warm the page cache
duration_s=$("$exe" run "$tmp/loop.stream" --algo odometry --no-figures -q -o "$tmp/run" >/dev/null &&
  sed -n 's/.*"duration_s": *\([0-9.eE+-]*\).*/\1/p' "$tmp/run/metrics.json" | head -1)
for i in $(seq "$n"); do wall_ms scenarios; done >"$tmp/scen_wall"
for i in $(seq "$n"); do rss_mib scenarios; done >"$tmp/scen_rss"
for i in $(seq "$n"); do wall_ms simulate loop -o "$tmp/loop.stream"; done >"$tmp/sim_wall"
for i in $(seq "$n"); do rss_mib simulate loop -o "$tmp/loop.stream"; done >"$tmp/sim_rss"
sim_ms=$(median <"$tmp/sim_wall")
echo "slambox scenarios:     median $(median <"$tmp/scen_wall") ms wall, $(median <"$tmp/scen_rss") MiB peak RSS ($n runs)"
echo "slambox simulate loop: median $sim_ms ms wall, $(median <"$tmp/sim_rss") MiB peak RSS, ${duration_s} s simulated:" \
  "$(awk -v d="$duration_s" -v w="$sim_ms" 'BEGIN {printf "%.0f", d * 1000 / w}')x real time ($n runs)"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
