#!/usr/bin/env bash
# The main job: set up, build, then run the default sweep (every built-in scenario x every
# module that applies x a few seeds) and write metrics, figures and a report under out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
rm -rf out/demo  # the demo's own folder: a rerun starts fresh
./build/app/slambox sweep scenarios/demo_sweep.yaml -j "${JOBS:-$(nproc)}" -o out/demo "$@"
echo "demo: open out/demo/report.html (summary in out/demo/summary.md)"
