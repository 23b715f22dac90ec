#!/usr/bin/env bash
# The relation table of the README ("Real laser logs") in one command: every CARMEN log
# of the public data that has a Kümmerle relations file is converted into a stream, then
# one sweep runs the modules on every stream with its relations, and the table is printed
# from the sweep's results.csv (Markdown; mean ± std of the relation errors, Hess et al.
# 2016 Table II convention; eval/README.md says how relations are matched).
#   usage: scripts/relation_table.sh [BUILD_DIR] [OUT_DIR]      (defaults: build, out/relation_table)
#   env:   SLAMBOX_DATA (default ../shared/data beside the project), JOBS (default 1),
#          ALGOS (default icp-poseslam,mrpt-icp-slam,mrpt-rbpf-slam)
# Streams are converted once and the sweep resumes (--resume): re-running only redoes what
# changed. Run times are in OUT_DIR/sweep/timing.csv.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
out=${2:-out/relation_table}
slambox=$build/app/slambox
[ -x "$slambox" ] || slambox=$build/slambox
[ -x "$slambox" ] || { echo "relation_table.sh: no slambox binary in $build (build it first)" >&2; exit 2; }
data=${SLAMBOX_DATA:-$here/../shared/data}
[ -d "$data/relations" ] || { echo "relation_table.sh: no $data/relations (set SLAMBOX_DATA)" >&2; exit 2; }
algos=${ALGOS:-icp-poseslam,mrpt-icp-slam,mrpt-rbpf-slam}
mkdir -p "$out/streams"

# MRPT's peers as MRPT's own configuration files for real laser logs set them up
# (slam/mrpt/README.md, "On real logs", lists each key and what cannot be expressed):
# mrpt-icp-slam from config_files/icp-slam/icp-slam_demo_classic.ini, mrpt-rbpf-slam from
# config_files/rbpf-slam/gridmapping_RBPF_ICPbased_intel.ini (a point map per particle,
# ICP-based optimal proposal, 10 particles; the same keys as tests/mrpt/rbpf_points_test.cpp).
# The grid-map file gridmapping_optimal_sampling.ini, used before, gave 5.27 ± 8.61 m on intel.
peer_settings() {
  case ",$algos," in *,mrpt-icp-slam,*|*,mrpt-rbpf-slam,*) echo "set:" ;; esac
  case ",$algos," in *,mrpt-icp-slam,*) cat <<'SET'
  algo.mrpt-icp-slam.icp_threshold_dist_m: 0.3
  algo.mrpt-icp-slam.icp_threshold_ang_deg: 5
  algo.mrpt-icp-slam.icp_alfa: 0.8
  algo.mrpt-icp-slam.icp_smallest_threshold_dist_m: 0.05
  algo.mrpt-icp-slam.icp_max_iterations: 80
  algo.mrpt-icp-slam.icp_points_decimation: 5
  algo.mrpt-icp-slam.min_icp_goodness: 0.40
  algo.mrpt-icp-slam.insertion_lin_distance_m: 1.2
  algo.mrpt-icp-slam.insertion_ang_distance_deg: 45
  algo.mrpt-icp-slam.localization_lin_distance_m: 0.2
  algo.mrpt-icp-slam.localization_ang_distance_deg: 5
  algo.mrpt-icp-slam.map_min_point_distance_m: 0.05
SET
  esac
  case ",$algos," in *,mrpt-rbpf-slam,*) cat <<'SET'
  algo.mrpt-rbpf-slam.map: points
  algo.mrpt-rbpf-slam.proposal: optimal
  algo.mrpt-rbpf-slam.particles: 10
  algo.mrpt-rbpf-slam.resampling: multinomial
  algo.mrpt-rbpf-slam.resample_ess_ratio: 0.5
  algo.mrpt-rbpf-slam.localize_lin_distance_m: 0.2
  algo.mrpt-rbpf-slam.localize_ang_distance_deg: 10
  algo.mrpt-rbpf-slam.insertion_lin_distance_m: 2.0
  algo.mrpt-rbpf-slam.insertion_ang_distance_deg: 30
  algo.mrpt-rbpf-slam.icp_min_quality: 0.80
  algo.mrpt-rbpf-slam.icp_algorithm: lm
  algo.mrpt-rbpf-slam.icp_max_iterations: 60
  algo.mrpt-rbpf-slam.icp_threshold_dist_m: 1.0
  algo.mrpt-rbpf-slam.icp_threshold_ang_deg: 5
  algo.mrpt-rbpf-slam.icp_alfa: 0.5
  algo.mrpt-rbpf-slam.icp_smallest_threshold_dist_m: 0.1
  algo.mrpt-rbpf-slam.points_min_distance_m: 0.05
  algo.mrpt-rbpf-slam.points_likelihood_max_corr_m: 5.0
  algo.mrpt-rbpf-slam.points_likelihood_var_m2: 0.05
SET
  esac
}

sweep=$out/relation_table.yaml
scenarios=""
relations=""
for rel in "$data"/relations/*.relations; do
  log=$(basename "$rel" .relations)
  clf=$data/rawlogs/$log.clf.bz2
  [ -f "$clf" ] || { echo "relation_table.sh: no $clf for $rel, skipped" >&2; continue; }
  stream=$out/streams/$log.stream
  [ -f "$stream" ] || "$slambox" convert carmen "$clf" -o "$stream"
  scenarios="$scenarios${scenarios:+, }$stream"
  relations="$relations${relations:+, }$stream: $rel"
done
[ -n "$scenarios" ] || { echo "relation_table.sh: no log with a relations file" >&2; exit 2; }
cat > "$sweep.tmp" <<EOF
# Written by scripts/relation_table.sh: the relation table's sweep (streams run once each).
scenarios: [$scenarios]
algorithms: [$algos]
seeds: 1
relations: {$relations}
timeout_s: 3600
$(peer_settings)
EOF
mv "$sweep.tmp" "$sweep"
"$slambox" sweep "$sweep" -j "${JOBS:-1}" --no-figures --resume -o "$out/sweep" >&2

# One row per log and module: columns looked up by name in results.csv's header.
awk -F, '
  NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; 
            print "| log | module | relations matched / unmatched | translational error [m] | rotational error [deg] | status |";
            print "|---|---|---|---|---|---|"; next }
  { n = split($c["scenario"], p, "/"); lg = p[n]; sub(/\.stream$/, "", lg);
    if ($c["relation_count"] == "") { printf "| %s | %s | - | - | - | %s |\n", lg, $c["algorithm"], $c["status"]; next }
    printf "| %s | %s | %d / %d | %.4f ± %.4f | %.3f ± %.3f | %s |\n", lg, $c["algorithm"],
           $c["relation_count"], $c["relation_unmatched"], $c["relation_trans_mean_m"], $c["relation_trans_std_m"],
           $c["relation_rot_mean_deg"], $c["relation_rot_std_deg"], $c["status"] }
' "$out/sweep/results.csv"
