#include "slam/icp_target.hpp"

#include <cassert>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>

namespace slambox {

struct PointsAdaptor {
  std::vector<Eigen::Vector2d> pts;
  size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(size_t i, size_t dim) const { return pts[i][static_cast<Eigen::Index>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};

using NanoflannTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointsAdaptor>, PointsAdaptor, 2,
                                        std::uint32_t>;

struct KdTree2d {
  explicit KdTree2d(std::vector<Eigen::Vector2d> points)
      : data{std::move(points)}, tree(2, data, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
  PointsAdaptor data;  // owned copy: the tree refers to it, so it must not move
  NanoflannTree tree;
};

Eigen::Vector2d FitNormal(const Eigen::Vector2d* points, int count) {
  if (count < 2) return Eigen::Vector2d::Zero();
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int i = 0; i < count; ++i) mean += points[i];
  mean /= count;
  double cxx = 0, cxy = 0, cyy = 0;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d d = points[i] - mean;
    cxx += d.x() * d.x();
    cxy += d.x() * d.y();
    cyy += d.y() * d.y();
  }
  if (cxx + cyy < 1e-18) return Eigen::Vector2d::Zero();
  // Major axis angle of the scatter ellipse: tan(2 phi) = 2 cxy / (cxx - cyy); normal is perpendicular.
  const double phi = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
  return {-std::sin(phi), std::cos(phi)};
}

IcpTarget MakeScanTarget(const ScanPoints& sp, const LaserScanEvent& geometry, const IcpTargetConfig& config) {
  IcpTarget t;
  t.points = sp.points;
  t.angle_min_rad = geometry.angle_min_rad;
  t.angle_increment_rad = geometry.angle_increment_rad;
  t.point_of_beam.assign(geometry.ranges_m.size(), -1);
  for (size_t k = 0; k < sp.beam.size(); ++k) t.point_of_beam[static_cast<size_t>(sp.beam[k])] = static_cast<int>(k);
  const int n = static_cast<int>(t.points.size());
  const int beams = static_cast<int>(t.point_of_beam.size());
  const double max2 = config.normal_max_neighbor_m * config.normal_max_neighbor_m;
  const bool full_circle = std::abs(beams * geometry.angle_increment_rad - 2 * M_PI) < 1e-6;
  t.normals.assign(static_cast<size_t>(n), Eigen::Vector2d::Zero());
  std::vector<Eigen::Vector2d> nb;
  for (int k = 0; k < n; ++k) {
    nb.clear();
    const int b0 = sp.beam[static_cast<size_t>(k)];
    for (int db = -config.normal_half_window; db <= config.normal_half_window; ++db) {
      int b = b0 + db;
      if (full_circle) b = (b + beams) % beams;
      if (b < 0 || b >= beams) continue;
      const int j = t.point_of_beam[static_cast<size_t>(b)];
      if (j >= 0 && (t.points[static_cast<size_t>(j)] - t.points[static_cast<size_t>(k)]).squaredNorm() <= max2)
        nb.push_back(t.points[static_cast<size_t>(j)]);
    }
    if (nb.size() >= 3) t.normals[static_cast<size_t>(k)] = FitNormal(nb.data(), static_cast<int>(nb.size()));
  }
  if (config.build_kd_tree) t.kd_tree = std::make_shared<const KdTree2d>(t.points);
  return t;
}

IcpTarget MakeCloudTarget(std::vector<Eigen::Vector2d> points, const IcpTargetConfig& config) {
  IcpTarget t;
  t.points = std::move(points);
  t.kd_tree = std::make_shared<const KdTree2d>(t.points);
  const size_t k = static_cast<size_t>(2 * config.normal_half_window + 1);
  const double max2 = config.normal_max_neighbor_m * config.normal_max_neighbor_m;
  std::vector<std::uint32_t> idx(k);
  std::vector<double> d2(k);
  std::vector<Eigen::Vector2d> nb;
  t.normals.assign(t.points.size(), Eigen::Vector2d::Zero());
  for (size_t i = 0; i < t.points.size(); ++i) {
    const size_t found = t.kd_tree->tree.knnSearch(t.points[i].data(), k, idx.data(), d2.data());
    nb.clear();
    for (size_t m = 0; m < found; ++m)
      if (d2[m] <= max2) nb.push_back(t.points[idx[m]]);
    if (nb.size() >= 3) t.normals[i] = FitNormal(nb.data(), static_cast<int>(nb.size()));
  }
  return t;
}

bool NearestByKdTree(const IcpTarget& target, const Eigen::Vector2d& q, int* index, double* dist2_m2) {
  assert(target.kd_tree && "IcpTarget built without a kd-tree");
  if (target.points.empty()) return false;
  std::uint32_t i = 0;
  double d2 = 0;
  if (target.kd_tree->tree.knnSearch(q.data(), 1, &i, &d2) == 0) return false;
  *index = static_cast<int>(i);
  *dist2_m2 = d2;
  return true;
}

bool NearestByProjection(const IcpTarget& target, const Eigen::Vector2d& q, int window_beams, int* index,
                         double* dist2_m2) {
  const int beams = static_cast<int>(target.point_of_beam.size());
  assert(beams > 0 && "IcpTarget has no beam index (not built from a scan)");
  const double bearing = std::atan2(q.y(), q.x());
  // Beam whose ray is nearest to the bearing, wrapped into [0, beams) for a full circle.
  const bool full_circle = std::abs(beams * target.angle_increment_rad - 2 * M_PI) < 1e-6;
  double f = NormalizeAngle(bearing - target.angle_min_rad) / target.angle_increment_rad;
  if (full_circle && f < 0) f += beams;
  const int center = static_cast<int>(std::lround(f));
  double best = std::numeric_limits<double>::infinity();
  int best_i = -1;
  for (int db = -window_beams; db <= window_beams; ++db) {
    int b = center + db;
    if (full_circle) b = ((b % beams) + beams) % beams;
    if (b < 0 || b >= beams) continue;
    const int j = target.point_of_beam[static_cast<size_t>(b)];
    if (j < 0) continue;
    const double d2 = (target.points[static_cast<size_t>(j)] - q).squaredNorm();
    if (d2 < best) {
      best = d2;
      best_i = j;
    }
  }
  if (best_i < 0) return false;
  *index = best_i;
  *dist2_m2 = best;
  return true;
}

}  // namespace slambox
