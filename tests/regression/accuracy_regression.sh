#!/usr/bin/env bash
# Accuracy regression: the sweep must not get worse than the committed baseline
# (per cell mean of ate_*, rpe_*, landmark_rmse_m) beyond 25 % + 5 mm.
set -euo pipefail
slambox=$1
src=$2
out=$(mktemp -d /tmp/slambox-accuracy.XXXXXX)
trap 'rm -rf "$out"' EXIT
"$slambox" sweep "$src/tests/regression/accuracy_sweep.yaml" -j 2 --no-figures -o "$out/sweep" \
  --check "$src/tests/regression/accuracy_baseline.csv" --tolerance 0.25 --tolerance-abs 0.005
