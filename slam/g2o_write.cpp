// Writing 2D pose(-landmark) graphs as g2o text (declared in slam/g2o_io.hpp; reading is in
// slam/g2o_io.cpp).
#include <algorithm>
#include <cstdio>

#include "core/atomic_file.hpp"
#include "slam/g2o_io.hpp"

namespace slambox {

namespace {
std::vector<int> WrittenLandmarkIds(const PoseGraph& graph, const std::vector<int>& vertex_ids,
                                    const std::vector<int>& landmark_ids) {
  const size_t n = graph.poses.size(), m = graph.landmarks.size();
  std::vector<int> pose_ids(n);
  for (size_t i = 0; i < n; ++i) pose_ids[i] = vertex_ids.empty() ? static_cast<int>(i) : vertex_ids.at(i);
  std::sort(pose_ids.begin(), pose_ids.end());
  const auto is_pose = [&](int id) { return std::binary_search(pose_ids.begin(), pose_ids.end(), id); };
  if (landmark_ids.size() == m && std::none_of(landmark_ids.begin(), landmark_ids.end(), is_pose)) return landmark_ids;
  std::vector<int> out;
  out.reserve(m);
  for (int id = 0; out.size() < m; ++id)  // the smallest ids no pose uses, in landmark order
    if (!is_pose(id)) out.push_back(id);
  return out;
}
}  // namespace

std::string FormatPoseGraph(const PoseGraph& graph, const std::vector<int>& vertex_ids,
                            const std::vector<int>& landmark_ids) {
  auto id = [&](int i) { return vertex_ids.empty() ? i : vertex_ids.at(i); };
  const std::vector<int> point_ids = WrittenLandmarkIds(graph, vertex_ids, landmark_ids);
  std::string out;
  char buf[512];
  for (size_t i = 0; i < graph.poses.size(); ++i) {
    const SE2& p = graph.poses[i];
    std::snprintf(buf, sizeof buf, "VERTEX_SE2 %d %.17g %.17g %.17g\n", id(static_cast<int>(i)), p.x, p.y, p.theta);
    out += buf;
  }
  for (size_t j = 0; j < graph.landmarks.size(); ++j) {
    const Eigen::Vector2d& l = graph.landmarks[j];
    std::snprintf(buf, sizeof buf, "VERTEX_XY %d %.17g %.17g\n", point_ids[j], l.x(), l.y());
    out += buf;
  }
  if (!graph.poses.empty()) {
    std::snprintf(buf, sizeof buf, "FIX %d\n", id(graph.anchor));
    out += buf;
  }
  for (const PoseGraphEdge& e : graph.edges) {
    const Eigen::Matrix3d& I = e.information;
    std::snprintf(buf, sizeof buf,
                  "EDGE_SE2 %d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", id(e.from),
                  id(e.to), e.T_from_to.x, e.T_from_to.y, e.T_from_to.theta, I(0, 0), I(0, 1), I(0, 2), I(1, 1),
                  I(1, 2), I(2, 2));
    out += buf;
  }
  for (const LandmarkEdge& e : graph.landmark_edges) {
    const Eigen::Matrix2d& I = e.information;
    std::snprintf(buf, sizeof buf, "EDGE_SE2_XY %d %d %.17g %.17g %.17g %.17g %.17g\n", id(e.pose),
                  point_ids.at(e.landmark), e.p_pose_landmark.x(), e.p_pose_landmark.y(), I(0, 0), I(0, 1), I(1, 1));
    out += buf;
  }
  return out;
}

void WritePoseGraph(const std::string& path, const PoseGraph& graph, const std::vector<int>& vertex_ids,
                    const std::vector<int>& landmark_ids) {
  WriteFileAtomic(path, FormatPoseGraph(graph, vertex_ids, landmark_ids));
}

}  // namespace slambox
