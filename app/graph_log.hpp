#pragma once
// `slambox convert graph`: a pose-landmark graph (slam/g2o_io.hpp: iSAM / GTSAM LANDMARK,
// g2o EDGE_SE2_XY) whose poses form one odometry chain -> LandmarkLog, which
// AssembleLandmarkLog (datasets/landmark_log.hpp) turns into a stream. The chain is the
// poses in ascending id order; the pose edge between each two consecutive ones is the
// odometry step, inverted where the file states it backwards. Pose edges off the chain
// (loop closures, a second edge between the same two poses) have no sensor in a stream:
// they are left out and counted. Ground truth is matched by file id (app/optimize_accuracy).
// In app/ because it joins slam's graph reader with app's ground-truth reader; datasets/
// sees core only.
#include <optional>
#include <string>
#include <vector>

#include "app/optimize_accuracy.hpp"
#include "datasets/landmark_log.hpp"
#include "slam/g2o_io.hpp"

namespace slambox {

struct GraphLogOptions {
  IsamNoise noise = IsamNoise::kAuto;    ///< how iSAM-family lines are read (slam/isam_noise.hpp)
  std::vector<std::string> groundtruth = {};  ///< ReadVertexTruth files (poses and/or landmarks); empty: none
};

struct GraphLogReport {
  long odometry_steps = 0;   ///< chain edges: poses - 1
  long reversed_steps = 0;   ///< of those, stated backwards in the file (pose k -> k-1), inverted
  long off_chain_edges = 0;  ///< pose edges not on the chain (loop closures, repeats), left out
  long sightings = 0;        ///< landmark edges
  long landmarks = 0;        ///< landmarks of the graph
  std::optional<IsamNoise> isam_noise;  ///< how the iSAM-family lines were read; nullopt: none (g2o)
};

struct GraphLog {
  LandmarkLog log;
  GraphLogReport report;
};

/// The chain of `file` (read from `name`). Throws InputError naming `name` for a graph with
/// no landmark edge, or with two consecutive poses that no edge joins (naming their ids).
GraphLog ChainLandmarkLog(const PoseGraphFile& file, const std::string& name);

/// Sets log->true_poses (one per pose of `file`) and log->true_landmarks (one per landmark
/// of `file`) from `truth`, matched by file id; each is left empty when `truth` has no
/// poses / no landmarks. Throws InputError naming `truth_name` for a pose or landmark of
/// the graph that `truth` lacks.
void AddVertexTruth(const PoseGraphFile& file, const VertexTruth& truth, const std::string& truth_name, LandmarkLog* log);

/// ReadPoseGraph, ChainLandmarkLog, then ReadVertexTruth of each ground-truth file.
GraphLog ReadGraphLog(const std::string& path, const GraphLogOptions& options = {});

}  // namespace slambox
