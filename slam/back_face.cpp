#include "slam/back_face.hpp"

#include <cassert>

#include "slam/icp_target.hpp"

namespace slambox {

void OrientNormalsTowards(IcpTarget* target, const std::vector<Eigen::Vector2d>& viewpoints) {
  assert(viewpoints.size() == target->points.size());
  for (size_t i = 0; i < target->normals.size(); ++i) {
    Eigen::Vector2d& n = target->normals[i];
    if (n.dot(viewpoints[i] - target->points[i]) < 0.0) n = -n;
  }
}

BackFaceResult BackFaces(const std::vector<Eigen::Vector2d>& scan, const IcpTarget& target, const SE2& T_target_scan,
                         const BackFaceSetting& setting) {
  BackFaceResult out;
  const Eigen::Vector2d sensor = T_target_scan.translation();
  const double max_d2 = setting.max_distance_m * setting.max_distance_m;
  for (const Eigen::Vector2d& p : scan) {
    int j = -1;
    double d2 = 0.0;
    if (!NearestByKdTree(target, T_target_scan * p, &j, &d2) || d2 > max_d2) continue;
    const Eigen::Vector2d& n = target.normals[static_cast<size_t>(j)];
    if (n.isZero()) continue;  // too few neighbours for a normal: no side
    ++out.matched;
    if (n.dot(sensor - target.points[static_cast<size_t>(j)]) < 0.0) ++out.back_faces;
  }
  out.fraction = out.matched > 0 ? static_cast<double>(out.back_faces) / out.matched : 0.0;
  return out;
}

}  // namespace slambox
