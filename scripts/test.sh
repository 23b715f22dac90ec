#!/usr/bin/env bash
# Set up, build, and run the whole test suite with CTest.
#   scripts/test.sh [CTEST ARGS...]              Release build in build/
#   scripts/test.sh --sanitize [CTEST ARGS...]   the same suite built with AddressSanitizer
#     + UndefinedBehaviorSanitizer (-fno-sanitize-recover=all: the first report fails the
#     test) in build-asan/. Leaks in our code fail too; scripts/lsan.supp suppresses only
#     third-party libraries, each with a reason.
#   scripts/test.sh --sanitize=core,sim,...      only the tests of those folders of tests/
#     (their CTest labels), building only their targets: what .ci/run runs.
set -euo pipefail
cd "$(dirname "$0")/.."
sanitize=""
labels=""
case "${1:-}" in
  --sanitize) sanitize=1; shift ;;
  --sanitize=*) sanitize=1; labels=${1#--sanitize=}; shift ;;
esac
bash scripts/setup.sh --with-slurm --with-browser
if [ -z "$sanitize" ]; then
  bash scripts/build.sh
  ctest --test-dir build --output-on-failure -j "${JOBS:-$(nproc)}" --timeout 600 "$@"
  exit
fi
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$PWD")}"
# EIGEN_MALLOC_ALREADY_ALIGNED=1: Eigen switches to its own offset allocator under ASan, but
# Debian's Ceres (libceres.a, linked statically, built without ASan) uses malloc directly;
# the two meet in shared template code and free each other's blocks ("bad-free" in
# ceres::Covariance). malloc is 16-byte aligned on x86-64 glibc and in ASan's allocator, and
# Eigen's own assert (active here: no NDEBUG) checks every block it gets.
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -DEIGEN_MALLOC_ALREADY_ALIGNED=1"
# -O1 -g1: line tables for the reports at about half the compile time of -O2 -g. The Python
# module is left out: it runs inside /usr/bin/python3, which is not built with ASan.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" -DSLAMBOX_BUILD_BENCH=OFF \
  -DSLAMBOX_BUILD_PYTHON=OFF -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
targets=()
label_args=()
if [ -n "$labels" ]; then
  for label in ${labels//,/ }; do
    [ -d "tests/$label" ] || { echo "test.sh: no folder tests/$label (labels are folders of tests/)" >&2; exit 2; }
    for file in tests/"$label"/*_test.cpp; do targets+=("${label}_$(basename "$file" .cpp)"); done
  done
  label_args=(-L "^(${labels//,/|})\$")
fi
cmake --build build-asan -j "${JOBS:-$(nproc)}" ${targets[@]+--target "${targets[@]}"}
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1:detect_stack_use_after_return=0"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Mesa's llvmpipe (behind OSMesa) keeps worker threads alive until exit; LeakSanitizer's
# stop-the-world tracer then crashed ("Tracer caught signal 11", 4 of 4 runs of
# NanModule.NonFiniteCovarianceIsDivergedAndNoFileHoldsNan's `slambox report`). Rendering in
# the calling thread avoids it; figures are the same either way (the render tests compare pixels).
export LP_NUM_THREADS=0
# Sanitized code runs 2-5x slower: the per-test timeout is doubled.
ctest --test-dir build-asan --output-on-failure -j "${JOBS:-$(nproc)}" --timeout 1200 ${label_args[@]+"${label_args[@]}"} "$@"
