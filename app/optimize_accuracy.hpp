#pragma once
// Accuracy of an optimized graph against ground truth for `slambox optimize --groundtruth`:
// true poses and landmarks matched to the graph's by file id, scored with the evaluator's
// own pieces and keys (eval/): ate_* without alignment (the graph's own gauge: its anchor),
// ate_aligned_* after SE(2) Umeyama, landmark_rmse_m after the same alignment.
#include <Eigen/Core>
#include <map>
#include <string>

#include "core/se2.hpp"
#include "eval/metrics.hpp"
#include "slam/g2o_io.hpp"

namespace slambox {

struct VertexTruth {
  std::map<int, SE2> poses;                  ///< by the graph file's pose id
  std::map<int, Eigen::Vector2d> landmarks;  ///< [m] by the graph file's landmark id
  std::map<int, int> pose_line, landmark_line;  ///< where each was read (for duplicate errors)
};

/// Adds one ground-truth file: `id x y theta` lines (poses), `id x y` lines (landmarks), or
/// g2o / TORO vertex lines (VERTEX_SE2, VERTEX2, VERTEX_XY; a graph's edge and FIX lines are
/// skipped); '#' starts a comment. Throws InputError (file, line, fix) for a malformed line,
/// an id given twice (also across files) or a file with neither poses nor landmarks.
void ReadVertexTruth(const std::string& path, VertexTruth* truth);

/// The ate_*, ate_aligned_*, matched_poses, alignment and landmark_* fields of Metrics for
/// `solved` (the graph of `file`, solved), NaN/null where nothing matches. Throws InputError
/// naming `truth_name` when no true pose matches a pose id of the graph.
Metrics ScoreAgainstTruth(const PoseGraphFile& file, const PoseGraph& solved, const VertexTruth& truth,
                          const std::string& truth_name);

}  // namespace slambox
