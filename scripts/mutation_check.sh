#!/usr/bin/env bash
# Mutation check of the test suite: applies each curated one-line bug of
# tests/mutation/mutants.tsv to the source tree, rebuilds what it touches (build/, ccache),
# runs the CTest suite and records which tests caught it; then restores the file.
# Every mutant must be caught. Not part of CI (a rebuild and the unit tests per mutant, the
# accuracy sweep too when they miss it): run it before a release-sized change.
#   bash scripts/mutation_check.sh [REGEX]   # only the mutants whose id matches REGEX
# Output: a Markdown table on stdout (id, file, what was planted, tests that failed) and
# exit 1 when a mutant survived. Each line of mutants.tsv is
#   id <TAB> file <TAB> original text <TAB> mutated text <TAB> what the bug is
# and the original text must occur exactly once in the file.
set -euo pipefail
cd "$(dirname "$0")/.."
filter=${1:-.}
table=tests/mutation/mutants.tsv
[ -x build/app/slambox ] || bash scripts/build.sh >/dev/null
jobs=${JOBS:-$(nproc)}
log=$(mktemp -d /tmp/slambox-mutation.XXXXXX)
restore() { [ -n "${current:-}" ] && git checkout -q -- "$current"; current=; }
trap 'restore' EXIT
survived=0
echo "| mutant | file | bug | caught by |"
echo "|---|---|---|---|"
while IFS=$'\t' read -r id file original mutated what; do
  [[ -z "$id" || "$id" == \#* ]] && continue
  [[ "$id" =~ $filter ]] || continue
  if ! git diff --quiet -- "$file"; then echo "mutation_check: $file has local changes; commit or stash them" >&2; exit 2; fi
  count=$(python3 -c 'import sys; print(open(sys.argv[1]).read().count(sys.argv[2]))' "$file" "$original")
  if [ "$count" != 1 ]; then echo "| $id | $file | $what | **pattern found $count times: fix mutants.tsv** |"; survived=1; continue; fi
  current=$file
  python3 -c 'import sys; p,a,b=sys.argv[1:4]; s=open(p).read(); open(p,"w").write(s.replace(a,b,1))' "$file" "$original" "$mutated"
  if ! cmake --build build -j "$jobs" >"$log/$id.build" 2>&1; then
    echo "| $id | $file | $what | build failed (see $log/$id.build) |"; survived=1; restore; continue
  fi
  # The unit and module tests first; the accuracy regression sweep (minutes) only when they
  # all pass, so a mutant costs one rebuild plus the tests that catch it.
  failed() { sed -n 's/^ *[0-9]* - \(.*\) (\(Failed\|Timeout\|SEGFAULT\|Subprocess aborted\|Exception\).*/\1/p' "$1" | sort -u | head -5 | paste -sd, - | sed 's/,/, /g'; }
  ctest --test-dir build -j "$jobs" --timeout 600 -LE "cluster|regression" >"$log/$id.ctest" 2>&1 || true
  caught=$(failed "$log/$id.ctest")
  if [ -z "$caught" ]; then
    ctest --test-dir build --timeout 900 -L regression >"$log/$id.regression" 2>&1 || true
    caught=$(failed "$log/$id.regression")
  fi
  if [ -z "$caught" ]; then caught="**survived**"; survived=1; fi
  echo "| $id | \`$file\` | $what | $caught |"
  restore
done <"$table"
cmake --build build -j "$jobs" >/dev/null 2>&1  # back to the unmutated binaries
exit $survived
