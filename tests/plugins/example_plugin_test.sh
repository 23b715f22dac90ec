#!/usr/bin/env bash
# The out-of-tree example plugin (examples/plugin) built against an installed slambox in a
# temporary folder, then run in a sweep next to the built-in `odometry`: its metrics are
# bit-identical to the built-in's, and results.csv is identical at -j1 and -j2.
# Usage: example_plugin_test.sh BUILD_DIR SOURCE_DIR   (the build must be complete)
set -euo pipefail
build=$1
src=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/slambox_example_plugin.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$src/examples/plugin" -B "$tmp/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  "${launcher[@]}" >"$tmp/configure.log"
cmake --build "$tmp/build" >"$tmp/build.log"
plugin="$tmp/build/example_odometry.so"
slambox="$tmp/prefix/bin/slambox"

"$slambox" algorithms --plugin "$plugin" | grep -q '^example-odometry .*(plugin example-odometry)$'

# The sweep file names the plugin; the second sweep passes it as --plugin instead.
cat >"$tmp/sweep.yaml" <<YAML
scenarios: [loop, landmarks]
algorithms: [odometry, example-odometry]
seeds: 2
set: {robot.laps: 1}
plugins: [$plugin]
YAML
grep -v '^plugins:' "$tmp/sweep.yaml" >"$tmp/sweep_cli.yaml"
"$slambox" sweep "$tmp/sweep.yaml" -j 1 --no-figures -o "$tmp/j1" >/dev/null
"$slambox" sweep "$tmp/sweep_cli.yaml" --plugin "$plugin" -j 2 --no-figures -o "$tmp/j2" >/dev/null
cmp "$tmp/j1/results.csv" "$tmp/j2/results.csv"

python3 - "$tmp/j1/results.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
by = {}
for r in rows:
    by.setdefault(r["run_id"], {})[r["algorithm"]] = r
assert len(by) == 4, f"expected 4 runs, got {len(by)}"
for run, algos in by.items():
    a, b = algos["odometry"], algos["example-odometry"]
    assert a["status"] == b["status"] == "ok", (run, a["status"], b["status"])
    diff = {k: (a[k], b[k]) for k in a if k != "algorithm" and a[k] != b[k]}
    assert not diff, f"run {run}: example-odometry differs from odometry: {diff}"
    assert a["ate_rmse_m"] not in ("", "nan"), a
print(f"example-odometry == odometry on {len(by)} runs, {len(rows[0])} columns each")
PY
