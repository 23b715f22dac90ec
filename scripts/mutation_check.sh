#!/usr/bin/env bash
# Mutation check of the test suite: applies each curated one-line bug of
# tests/mutation/mutants.tsv to the source tree, rebuilds only what the suite runs
# (target slambox_test_suite: no benchmark; ccache), runs the CTest suite and records which
# tests caught it; then puts the file back byte for byte. Every mutant must be caught.
# The suite runs in stages and stops at the first stage that fails: the layers' unit and
# module tests (labels core sim slam eval datasets mrpt), then the end-to-end ones (app,
# render, python, plugins), then the accuracy regression sweep; "caught by" lists the failing
# tests of that stage. Not part of CI (a rebuild and one to three stages per mutant): run it
# before a release-sized change.
#   bash scripts/mutation_check.sh [REGEX]   # only the mutants whose id matches REGEX
#   JOBS=2 BUILD_DIR=build                   # the defaults: nproc, build/ (configured if absent)
# Each stage first runs once unmutated: a test failing there would "catch" every mutant, so
# the check stops (exit 2). Output: a Markdown table on stdout (mutant, file, bug, tests that
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
plant() {  # plant FILE ORIGINAL MUTATED
  cp "$1" "$log/original"
  current=$1
  python3 -c 'import sys; p,a,b=sys.argv[1:4]; s=open(p).read(); open(p,"w").write(s.replace(a,b,1))' "$1" "$2" "$3"
}
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
  local n names
  n=$(grep -c . "$1" || true)
  names=$(head -5 "$1" | paste -sd, - | sed 's/,/, /g')
  if [ "$n" -gt 5 ]; then printf '%s (+%d more)' "$names" $((n - 5)); else printf '%s' "$names"; fi
}
stages=(unit end-to-end regression)
declare -A stage_args=(
  [unit]='-L ^(core|sim|slam|eval|datasets|mrpt)$'
  [end-to-end]='-LE ^(core|sim|slam|eval|datasets|mrpt|cluster|regression)$'
  [regression]='-L ^regression$')
declare -A stage_clean=()
run_stage() {  # run_stage STAGE LOG: that stage's tests into LOG
  local j=$jobs
  [ "$1" = regression ] && j=1  # one sweep, itself parallel
  # shellcheck disable=SC2086
  ctest --test-dir "$build" -j "$j" --timeout 900 ${stage_args[$1]} </dev/null >"$2" 2>&1 || true
}
check_clean() {  # the stage passes on the unmutated tree (once; the tree is unmutated here)
  [ -n "${stage_clean[$1]:-}" ] && return 0
  run_stage "$1" "$log/unmutated.$1"
  failed_tests "$log/unmutated.$1" >"$log/unmutated.$1.failed"
  if [ -s "$log/unmutated.$1.failed" ] || ! grep -q '100% tests passed' "$log/unmutated.$1"; then
    echo "mutation_check: the unmutated $1 tests fail ($(summarize "$log/unmutated.$1.failed")); see $log/unmutated.$1" >&2
    exit 2
  fi
  stage_clean[$1]=1
}

rebuild "$log/unmutated.build" || { echo "mutation_check: the unmutated tree does not build (see $log/unmutated.build)" >&2; exit 2; }
check_clean unit

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
  plant "$file" "$original" "$mutated"
  if ! rebuild "$log/$id.build"; then
    echo "| $id | \`$file\` | $what | **build failed** (see $log/$id.build) | $((SECONDS - start)) |"; survived=1; restore; continue
  fi
  caught="**survived**"
  for stage in "${stages[@]}"; do
    if [ -z "${stage_clean[$stage]:-}" ]; then  # the stage's unmutated run, once, when first needed
      restore; rebuild "$log/unmutated.build" || exit 2; check_clean "$stage"
      plant "$file" "$original" "$mutated"; rebuild "$log/$id.build" || exit 2
    fi
    run_stage "$stage" "$log/$id.$stage"
    failed_tests "$log/$id.$stage" >"$log/$id.failed"
    if [ -s "$log/$id.failed" ]; then caught="$(summarize "$log/$id.failed") ($stage)"; break; fi
  done
  [ "$caught" = "**survived**" ] && survived=1
  restore
  echo "| $id | \`$file\` | $what | $caught | $((SECONDS - start)) |"
done 3<"$table"  # fd 3: a test that reads stdin must not eat the table
echo "mutation_check: $((SECONDS - start_all)) s for the mutants (after the unmutated build and unit tests)" >&2
rebuild "$log/final.build" || true  # back to the unmutated binaries
exit $survived
