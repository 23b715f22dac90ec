#!/bin/bash
# scripts/random_scenarios.py writes only scenarios slambox accepts: batches 8 and 10 once drew
# people whose lanes ran through pillars (lidar8_2, lidar10_5: "mover 1's path ... runs into the
# occupied cells"); those movers are now left out. Every file of the drawn scenarios must pass
# `slambox scenario show`. Usage: random_scenarios_test.sh SLAMBOX SOURCE_DIR (77 = skipped).
set -u
slambox=$1; src=$2
source "$src/tests/scripts/generator_env.sh"
"$python" "$src/scripts/random_scenarios.py" "$out" lidar 3 8 > /dev/null || exit 1
"$python" "$src/scripts/random_scenarios.py" "$out" lidar 6 10 > /dev/null || exit 1
"$python" "$src/scripts/random_scenarios.py" "$out" lm 4 10 > /dev/null || exit 1
status=0; count=0
for f in "$out"/lidar*_[0-9].yaml "$out"/lm*_[0-9].yaml; do
  count=$((count + 1))
  (cd "$out" && "$slambox" scenario show "$(basename "$f")" > /dev/null) || { echo "refused: $(basename "$f")"; status=1; }
done
grep -q "movers:" "$out/lidar10_5.yaml" || { echo "lidar10_5 lost the mover whose lane is clear"; status=1; }
echo "$count scenarios checked"
exit $status
