#!/usr/bin/env bash
# Mutation check of the test suite: applies each curated one-line bug of
# tests/mutation/mutants.tsv to the source tree, rebuilds only what the suite runs
# (target slambox_test_suite: no benchmark; ccache), runs the CTest suite and records which
# tests caught it; then puts the file back byte for byte. Every mutant must be caught.
# Not part of CI (per mutant a rebuild and the suite, the accuracy sweep too when the suite
# misses it): run it before a release-sized change.
#   bash scripts/mutation_check.sh [REGEX]   # only the mutants whose id matches REGEX
#   JOBS=2 BUILD_DIR=build                   # the defaults: nproc, build/ (configured if absent)
# The unmutated suite runs first: a test failing there would "catch" every mutant, so the
# check stops (exit 2). Output: a Markdown table on stdout (mutant, file, bug, tests that
# failed, seconds for rebuild + tests) and exit 1 when a mutant survived. Each line of
# mutants.tsv is
#   id <TAB> file <TAB> original text <TAB> mutated text <TAB> what the bug is
# and the original text must occur exactly once in the file.
set -euo pipefail
cd "$(dirname "$0")/.."
filter=${1:-.}
table=tests/mutation/mutants.tsv
build=${BUILD_DIR:-build}
jobs=${JOBS:-$(nproc)}
log=$(mktemp -d "${TMPDIR:-/tmp}/slambox-mutation.XXXXXX")
echo "mutation_check: logs in $log" >&2

current=  # the file that holds a mutant right now, its original bytes in $log/original
restore() {
  if [ -n "$current" ]; then cat "$log/original" >"$current"; current=; fi  # new mtime: rebuilt next time
}
trap 'restore' EXIT
trap 'restore; exit 130' INT TERM

if [ ! -f "$build/CMakeCache.txt" ]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >"$log/configure" 2>&1
fi
rebuild() { cmake --build "$build" -j "$jobs" --target slambox_test_suite >"$1" 2>&1; }

# The names in the "The following tests FAILED:" list of a CTest log (any status: Failed,
# Timeout, SEGFAULT, Subprocess aborted, Not Run, ...), one a line.
failed_tests() {
  sed -n '/^The following tests FAILED:/,/^Errors while running/p' "$1" |
    sed -n 's/^[[:space:]]*[0-9]\+ - \(.*\) (.*)$/\1/p' | sort -u
}
# "A, B, C, D, E (+N more)" from a list of names.
summarize() {
  local n; n=$(grep -c . "$1" || true)
  head -5 "$1" | paste -sd, - | sed 's/,/, /g'
  [ "$n" -gt 5 ] && printf ' (+%d more)' $((n - 5))
  return 0
}
suite() { ctest --test-dir "$build" -j "$jobs" --timeout 600 -LE "cluster|regression" </dev/null >"$1" 2>&1 || true; }
regression() { ctest --test-dir "$build" --timeout 900 -L regression </dev/null >"$1" 2>&1 || true; }

rebuild "$log/unmutated.build" || { echo "mutation_check: the unmutated tree does not build (see $log/unmutated.build)" >&2; exit 2; }
suite "$log/unmutated.ctest"
failed_tests "$log/unmutated.ctest" >"$log/unmutated.failed"
if [ -s "$log/unmutated.failed" ] || ! grep -q '100% tests passed' "$log/unmutated.ctest"; then
  echo "mutation_check: the unmutated suite fails ($(summarize "$log/unmutated.failed")); see $log/unmutated.ctest" >&2
  exit 2
fi

survived=0
start_all=$SECONDS
echo "| mutant | file | bug | caught by | s |"
echo "|---|---|---|---|---|"
while IFS=$'\t' read -r -u 3 id file original mutated what; do
  [[ -z "$id" || "$id" == \#* ]] && continue
  [[ "$id" =~ $filter ]] || continue
  count=$(python3 -c 'import sys; print(open(sys.argv[1]).read().count(sys.argv[2]))' "$file" "$original")
  if [ "$count" != 1 ]; then echo "| $id | \`$file\` | $what | **pattern found $count times: fix mutants.tsv** | |"; survived=1; continue; fi
  start=$SECONDS
  cp "$file" "$log/original"
  current=$file
  python3 -c 'import sys; p,a,b=sys.argv[1:4]; s=open(p).read(); open(p,"w").write(s.replace(a,b,1))' "$file" "$original" "$mutated"
  if ! rebuild "$log/$id.build"; then
    echo "| $id | \`$file\` | $what | **build failed** (see $log/$id.build) | $((SECONDS - start)) |"; survived=1; restore; continue
  fi
  # The unit and module tests first; the accuracy regression sweep (a minute) only when they
  # all pass, so a mutant costs one rebuild plus the suite.
  suite "$log/$id.ctest"
  failed_tests "$log/$id.ctest" >"$log/$id.failed"
  if [ ! -s "$log/$id.failed" ]; then
    regression "$log/$id.regression"
    failed_tests "$log/$id.regression" >"$log/$id.failed"
  fi
  if [ -s "$log/$id.failed" ]; then caught=$(summarize "$log/$id.failed"); else caught="**survived**"; survived=1; fi
  restore
  echo "| $id | \`$file\` | $what | $caught | $((SECONDS - start)) |"
done 3<"$table"  # fd 3: a test that reads stdin must not eat the table
echo "mutation_check: $((SECONDS - start_all)) s for the mutants (after the unmutated build and suite)" >&2
rebuild "$log/final.build" || true  # back to the unmutated binaries
exit $survived
