#!/usr/bin/env bash
# Installs what is missing (scripts/setup.sh), then configures and builds slambox in
# build/ (Release unless BUILD_TYPE is set). JOBS defaults to the number of cores.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# ccache (installed by setup.sh) makes a rebuild of an unchanged tree, e.g. a fresh clone
# on a machine that built it before, take seconds; CCACHE_BASEDIR lets clones share it.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$PWD")}"
cmake -S . -B build -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" "${launcher[@]}" >/dev/null
cmake --build build -j "${JOBS:-$(nproc)}"
