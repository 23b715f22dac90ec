// `slambox eval --gt GT --est EST`: scores any TUM or KITTI trajectory against another
// (also files from other tools; 3D TUM files are reduced to x, y and yaw) with the same
// evaluator `slambox run` uses. --json prints one algorithm's metrics.json entry;
// --save-results FILE.zip writes evo's result archive (for evo_res).
// `--relations FILE` (with or without --gt) scores it on Kümmerle relations; their times
// are the log's clock, mapped by `--stream` (a converted log's header) or `--time-origin-s`.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "app/eval_options.hpp"
#include "core/error.hpp"
#include "core/kitti_poses.hpp"
#include "core/stream_io.hpp"
#include "core/tum.hpp"
#include "eval/evaluate.hpp"
#include "eval/evo_result.hpp"

namespace slambox {

namespace {
struct EvalArgs {
  std::string gt_path;
  std::string est_path;
  EvalChoices trajectory;  ///< --align, --delta, --delta-unit, --all-pairs, ... (app/eval_options)
  bool json = false;
  std::string save_results;
  std::string relations_path;
  std::string stream_path;       ///< the converted log, for its time origin
  double time_origin_s = 0.0;
  bool time_origin_given = false;
  double relation_max_diff_s = RelationMatchOptions{}.max_time_diff_s;
};

// TUM or KITTI by content. KITTI poses are stamped with their line index, so two KITTI
// files match line by line (evo_ape kitti); a KITTI file cannot be matched to a TUM one.
struct Trajectories {
  std::vector<StampedPose> gt, est;
};
Trajectories ReadTrajectories(const std::string& gt_path, const std::string& est_path) {
  const TrajectoryFormat gt_format = DetectTrajectoryFormat(gt_path);
  const TrajectoryFormat est_format = DetectTrajectoryFormat(est_path);
  if (gt_format != est_format)
    throw InputError(gt_format == TrajectoryFormat::kKitti ? gt_path : est_path, 0,
                     "a KITTI file (no timestamps) cannot be matched to a TUM file",
                     "give both files as TUM, or both as KITTI with one line per matched pose");
  if (gt_format == TrajectoryFormat::kTum) return {ReadTum(gt_path), ReadTum(est_path)};
  Trajectories t{ReadKittiPoses(gt_path), ReadKittiPoses(est_path)};
  if (t.gt.size() != t.est.size())
    throw InputError(est_path, 0,
                     "KITTI files must have the same number of poses (" + std::to_string(t.gt.size()) + " vs " +
                         std::to_string(t.est.size()) + ")",
                     "write both at the same matched poses (slambox run --format kitti does)");
  return t;
}

EvalOptions ToOptions(const EvalArgs& a) {
  EvalOptions o = TrajectoryEvalOptions(a.trajectory, OptionSpelling::kCommandLine);
  if (a.relations_path.empty()) {
    if (!a.stream_path.empty() || a.time_origin_given)
      throw InputError(a.stream_path.empty() ? "--time-origin-s" : "--stream", 0, "only used with --relations",
                       "add --relations FILE or drop it");
    return o;
  }
  if (!a.stream_path.empty() && a.time_origin_given)
    throw InputError("--time-origin-s", 0, "--stream already gives the time origin", "give one of them");
  if (!(a.relation_max_diff_s >= 0.0))
    throw InputError("--relation-t-max-diff", 0, "must be >= 0", "give e.g. 0.005");
  o.relations = ReadRelations(a.relations_path);
  o.relation_matching.max_time_diff_s = a.relation_max_diff_s;
  o.relation_matching.time_origin_s = a.time_origin_s;
  if (!a.stream_path.empty()) {
    const StreamHeader h = ReadStreamHeader(a.stream_path);
    if (!h.time_origin_s)
      throw InputError(a.stream_path, 0, "the stream records no time origin (simulated, or converted by an older slambox)",
                       "re-convert the log with `slambox convert carmen LOG -o STREAM`, or give --time-origin-s");
    o.relation_matching.time_origin_s = *h.time_origin_s;
  }
  return o;
}

void PrintTable(const nlohmann::json& m, std::ostream& out) {
  auto row = [&](const char* label, const char* key, const char* unit) {
    char line[160];
    if (!m.contains(key) || m[key].is_null())
      std::snprintf(line, sizeof line, "  %-28s %12s\n", label, "-");
    else if (m[key].is_number_integer())
      std::snprintf(line, sizeof line, "  %-28s %12lld %s\n", label, m[key].get<long long>(), unit);
    else
      std::snprintf(line, sizeof line, "  %-28s %12.6g %s\n", label, m[key].get<double>(), unit);
    out << line;
  };
  out << "matched poses " << m["matched_poses"] << ", ground-truth path " << m["distance_m"] << " m, status "
      << m["status"].get<std::string>();
  if (m.contains("reason")) out << " (" << m["reason"].get<std::string>() << ")";
  out << "\n";
  out << "ATE (evo APE, translation)\n";
  for (const char* s : {"rmse", "mean", "median", "std", "min", "max"}) {
    const std::string key = std::string("ate_") + s + "_m";
    row(s, key.c_str(), "m");
  }
  row("aligned rmse (SE(2) Umeyama)", "ate_aligned_rmse_m", "m");
  row("heading rmse", "heading_rmse_deg", "deg");
  out << "RPE (delta " << m["rpe_delta"] << " " << m["rpe_delta_unit"].get<std::string>()
      << (m["rpe_all_pairs"].get<bool>() ? ", all pairs" : ", consecutive pairs") << ")\n";
  row("pairs", "rpe_pairs", "");
  row("translation rmse", "rpe_trans_rmse_m", "m");
  row("translation mean", "rpe_trans_mean_m", "m");
  row("rotation rmse", "rpe_rot_rmse_deg", "deg");
  row("rotation mean", "rpe_rot_mean_deg", "deg");
  out << "KITTI segments (100..800 m)\n";
  row("segments", "kitti_segments", "");
  row("translation", "kitti_trans_percent", "%");
  row("rotation", "kitti_rot_deg_per_m", "deg/m");
  out << "Relations (Kümmerle et al. 2009)\n";
  row("relations", "relation_count", "");
  row("unmatched", "relation_unmatched", "");
  row("translation mean", "relation_trans_mean_m", "m");
  row("translation std", "relation_trans_std_m", "m");
  row("rotation mean", "relation_rot_mean_deg", "deg");
  row("rotation std", "relation_rot_std_deg", "deg");
}
}  // namespace

void AddEvalCommand(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  CLI::App* cmd = app.add_subcommand("eval", "score an estimated TUM trajectory against ground truth (evo's definitions)");
  cmd->add_option("--gt", args->gt_path,
                  "ground-truth trajectory (TUM: t x y z qx qy qz qw, or KITTI: 3 x 4 poses); needs --gt or --relations");
  cmd->add_option("--est", args->est_path, "estimated trajectory (TUM, or KITTI with a KITTI --gt)")->required();
  cmd->add_option("--align", args->trajectory.align,
                  "alignment before ate_*: none (default), se2 (Umeyama, evo -a) or origin (evo --align_origin)");
  cmd->add_option("--delta", args->trajectory.delta, "RPE delta (default 1)");
  cmd->add_option("--delta-unit", args->trajectory.delta_unit, "RPE delta unit: m (default), f (frames) or d (degrees)");
  cmd->add_flag("--all-pairs", args->trajectory.all_pairs, "RPE over all pairs instead of consecutive ones (evo --all_pairs)");
  cmd->add_flag("--pairs-from-reference", args->trajectory.pairs_from_reference,
                "choose RPE pairs on the ground truth (evo --pairs_from_reference)");
  cmd->add_option("--t-max-diff", args->trajectory.t_max_diff_s, "max. timestamp difference for matching [s] (default 0.01)");
  cmd->add_flag("--interpolate", args->trajectory.interpolate, "interpolate ground truth at the estimate's timestamps");
  cmd->add_flag("--json", args->json, "print the metrics as JSON (the keys of one metrics.json entry)");
  cmd->add_option("--save-results", args->save_results,
                  "write evo's result archive (info.json, stats.json, error_array.npz, ...) for evo_res; needs --gt");
  cmd->add_option("--relations", args->relations_path,
                  "Kümmerle relations file (t_i t_j dx dy dz roll pitch dtheta, the log's clock): relation_* on it");
  cmd->add_option("--stream", args->stream_path, "the converted log the estimate came from: its time origin maps the relations");
  cmd->add_option("--time-origin-s", args->time_origin_s, "the log's clock at estimate time 0 [s] (default 0: the estimate uses the log's clock)")
      ->each([args](const std::string&) { args->time_origin_given = true; });
  cmd->add_option("--relation-t-max-diff", args->relation_max_diff_s,
                  "max. distance from a relation time to the nearest estimate pose [s] (default 0.005)");
  cmd->callback([args] {
    if (args->gt_path.empty() && args->relations_path.empty())
      throw InputError("--gt", 0, "nothing to score against", "give --gt GT.tum, --relations FILE, or both");
    if (!args->save_results.empty() && args->gt_path.empty())
      throw InputError("--save-results", 0, "evo's result archive holds the APE: it needs ground truth", "give --gt GT");
    const EvalOptions options = ToOptions(*args);
    GroundTruth gt;
    Trajectories files;
    if (!args->gt_path.empty()) {
      files = ReadTrajectories(args->gt_path, args->est_path);
      gt.trajectory = std::move(files.gt);
      if (gt.trajectory.empty()) throw InputError(args->gt_path, 0, "no pose in the file", "give a non-empty TUM file");
    } else {
      files.est = ReadTum(args->est_path);  // relations need the estimate's timestamps
    }
    Estimate est;
    for (const auto& p : files.est) est.trajectory.push_back({p.t_s, p.pose, Eigen::Matrix3d::Zero(), false});
    if (est.trajectory.empty())
      throw InputError(args->est_path, 0, "no pose in the file", "give a non-empty TUM file");
    const Evaluation ev = EvaluateEstimate(gt, est, options);
    if (!args->gt_path.empty())
      RequireMatchedPoses(ev.metrics, args->trajectory, args->est_path, OptionSpelling::kCommandLine);
    if (!options.relations.empty() && ev.metrics.relation.relations == 0)
      throw InputError(args->est_path, 0,
                       "no relation time has an estimate pose within " + std::to_string(args->relation_max_diff_s) +
                           " s (time origin " + std::to_string(options.relation_matching.time_origin_s) + " s)",
                       "give --stream STREAM (the converted log) or --time-origin-s, or the relations of this log");
    if (!args->save_results.empty()) {
      auto stem = [](const std::string& path) { return std::filesystem::path(path).stem().string(); };
      WriteEvoApeResult(args->save_results, ev, options.align, {stem(args->gt_path), stem(args->est_path)});
    }
    if (args->json)
      std::cout << ToJson(ev.metrics).dump(2) << "\n";
    else
      PrintTable(ToJson(ev.metrics), std::cout);
  });
}

}  // namespace slambox
