#!/usr/bin/env bash
# Set up, build, and run the whole test suite with CTest.
#   scripts/test.sh [CTEST ARGS...]              Release build in build/
#   scripts/test.sh --sanitize [CTEST ARGS...]   the same suite built with AddressSanitizer
#     + UndefinedBehaviorSanitizer (-fno-sanitize-recover=all: the first report fails the
#     test) in build-asan/. Leaks in our code fail too; scripts/lsan.supp suppresses only
#     third-party libraries, each with a reason.
set -euo pipefail
cd "$(dirname "$0")/.."
sanitize=""
if [ "${1:-}" = "--sanitize" ]; then sanitize=1; shift; fi
bash scripts/setup.sh --with-slurm --with-browser
if [ -z "$sanitize" ]; then
  bash scripts/build.sh
  ctest --test-dir build --output-on-failure -j "${JOBS:-$(nproc)}" --timeout 600 "$@"
  exit
fi
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$PWD")}"
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" -DSLAMBOX_BUILD_BENCH=OFF \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build build-asan -j "${JOBS:-$(nproc)}"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1:detect_stack_use_after_return=0"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Sanitized code runs 2-5x slower: the per-test timeout is doubled.
ctest --test-dir build-asan --output-on-failure -j "${JOBS:-$(nproc)}" --timeout 1200 "$@"
