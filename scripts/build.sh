#!/usr/bin/env bash
# Installs what is missing (scripts/setup.sh), then configures and builds slambox in
# build/ (Release unless BUILD_TYPE is set). JOBS defaults to the number of cores.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" >/dev/null
cmake --build build -j "${JOBS:-$(nproc)}"
