#!/usr/bin/env bash
# Accuracy regression: no run of the sweep may get worse than its own baseline run (same
# scenario, seed and module; runs are deterministic) by more than 10 % (+ 1e-6 so that an
# exact zero stays comparable), no run that was ok may fail or diverge, and no row may go
# missing (`slambox sweep --check`, app/sweep_check.hpp).
set -euo pipefail
slambox=$1
src=$2
out=$(mktemp -d /tmp/slambox-accuracy.XXXXXX)
trap 'rm -rf "$out"' EXIT
"$slambox" sweep "$src/tests/regression/accuracy_sweep.yaml" -j 2 --no-figures -o "$out/sweep" \
  --check "$src/tests/regression/accuracy_baseline.csv" --tolerance 0.10 --tolerance-abs 1e-6
