#include "app/graph_log.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"

namespace slambox {

namespace {

struct Step {
  SE2 increment;                ///< pose k in pose k-1's frame
  Eigen::Matrix3d covariance;   ///< over (x [m], y [m], theta [rad])
};

// An edge stated as pose k-1 in pose k's frame, T, becomes T^-1. First order, its
// covariance maps by J = d(T^-1)/dT with T^-1 = (-c x - s y, s x - c y, -theta).
Step Inverted(const SE2& T, const Eigen::Matrix3d& covariance) {
  const double c = std::cos(T.theta), s = std::sin(T.theta), x = T.x, y = T.y;
  Eigen::Matrix3d J_inv_T;
  J_inv_T << -c, -s, s * x - c * y,
              s, -c, c * x + s * y,
              0.0, 0.0, -1.0;
  return {T.inverse(), J_inv_T * covariance * J_inv_T.transpose()};
}

std::string Joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

GraphLog ChainLandmarkLog(const PoseGraphFile& file, const std::string& name) {
  const PoseGraph& g = file.graph;
  if (g.landmark_edges.empty())
    throw InputError(name, 0, "the graph has no landmark edge: a stream of it would have no sensor",
                     "give a pose-landmark graph (LANDMARK, EDGE_SE2_XY lines); pose graphs are for `slambox optimize`");
  GraphLog out;
  out.report.isam_noise = file.isam_noise;
  const size_t n = g.poses.size();
  std::vector<const PoseGraphEdge*> step(n, nullptr);  // step[k]: the first edge joining poses k-1 and k
  for (const PoseGraphEdge& e : g.edges) {
    const size_t k = static_cast<size_t>(std::max(e.from, e.to));
    if (std::abs(e.from - e.to) != 1 || step[k]) {
      ++out.report.off_chain_edges;
      continue;
    }
    step[k] = &e;
  }
  LandmarkLog& log = out.log;
  for (size_t k = 1; k < n; ++k) {
    if (!step[k])
      throw InputError(name, 0,
                       "no pose edge joins poses " + std::to_string(file.vertex_ids[k - 1]) + " and " +
                           std::to_string(file.vertex_ids[k]) + " (consecutive in id order)",
                       "the poses must form one odometry chain: an edge between each two consecutive pose ids");
    const PoseGraphEdge& e = *step[k];
    Step s{e.T_from_to, e.information.inverse()};
    if (e.from > e.to) s = Inverted(s.increment, s.covariance), ++out.report.reversed_steps;
    log.increments.push_back(s.increment);
    log.increment_covariances.push_back(s.covariance);
  }
  for (const LandmarkEdge& e : g.landmark_edges)
    log.sightings.push_back({e.pose, file.landmark_ids[static_cast<size_t>(e.landmark)], e.p_pose_landmark,
                             e.information.inverse()});
  out.report.odometry_steps = static_cast<long>(log.increments.size());
  out.report.sightings = static_cast<long>(log.sightings.size());
  out.report.landmarks = static_cast<long>(g.landmarks.size());
  return out;
}

namespace {

std::vector<SE2> TruePoses(const PoseGraphFile& file, const VertexTruth& truth, const std::string& truth_name) {
  std::vector<SE2> poses;
  if (truth.poses.empty()) return poses;
  for (const int id : file.vertex_ids) {
    const auto it = truth.poses.find(id);
    if (it == truth.poses.end())
      throw InputError(truth_name, 0, "no true pose for pose id " + std::to_string(id) + " of the graph",
                       "give a true pose ('id x y theta') for every pose of the graph");
    poses.push_back(it->second);
  }
  return poses;
}

std::map<int, Eigen::Vector2d> TrueLandmarks(const PoseGraphFile& file, const VertexTruth& truth,
                                             const std::string& truth_name) {
  std::map<int, Eigen::Vector2d> landmarks;
  if (truth.landmarks.empty()) return landmarks;
  for (const int id : file.landmark_ids) {
    const auto it = truth.landmarks.find(id);
    if (it == truth.landmarks.end())
      throw InputError(truth_name, 0, "no true position for landmark id " + std::to_string(id) + " of the graph",
                       "give a true landmark ('id x y') for every landmark of the graph");
    landmarks[id] = it->second;
  }
  return landmarks;
}

}  // namespace

void AddVertexTruth(const PoseGraphFile& file, const VertexTruth& truth, const std::string& truth_name, LandmarkLog* log) {
  log->true_poses = TruePoses(file, truth, truth_name);
  log->true_landmarks = TrueLandmarks(file, truth, truth_name);
}

GraphLog ReadGraphLog(const std::string& path, const GraphLogOptions& options) {
  const PoseGraphFile file = ReadPoseGraph(path, {.isam_noise = options.noise});
  GraphLog out = ChainLandmarkLog(file, path);
  VertexTruth truth;
  std::vector<std::string> pose_files, landmark_files;  // which file gave what, named by the errors
  for (const std::string& truth_path : options.groundtruth) {
    const size_t poses = truth.poses.size(), landmarks = truth.landmarks.size();
    ReadVertexTruth(truth_path, &truth);
    if (truth.poses.size() > poses) pose_files.push_back(truth_path);
    if (truth.landmarks.size() > landmarks) landmark_files.push_back(truth_path);
  }
  out.log.true_poses = TruePoses(file, truth, Joined(pose_files));
  out.log.true_landmarks = TrueLandmarks(file, truth, Joined(landmark_files));
  return out;
}

}  // namespace slambox
