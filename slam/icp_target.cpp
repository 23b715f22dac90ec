#include "slam/icp_target.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <mutex>
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

struct LazyKdTree {
  std::once_flag once;
  std::unique_ptr<const KdTree2d> tree;
  const KdTree2d& Get(const std::vector<Eigen::Vector2d>& points) {
    std::call_once(once, [&] { tree = std::make_unique<const KdTree2d>(points); });
    return *tree;
  }
};

namespace {

// FitNormal's body, inlined into MakeScanTarget's per-point loop so that consecutive fits
// overlap; no data-dependent branch after the degenerate-input checks.
[[gnu::always_inline]] inline Eigen::Vector2d FitNormalInline(const Eigen::Vector2d* points, int count) {
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
  // Smaller eigenvalue of [[cxx, cxy], [cxy, cyy]] and its eigenvector (no trigonometry):
  // (C - l I) v = 0 gives v = (cxy, l - cxx) or (l - cyy, cxy); take the better conditioned.
  const double half_diff = 0.5 * (cxx - cyy);
  const double l = 0.5 * (cxx + cyy) - std::sqrt(half_diff * half_diff + cxy * cxy);
  const Eigen::Vector2d v1(cxy, l - cxx), v2(l - cyy, cxy);
  const bool first = v1.squaredNorm() > v2.squaredNorm();
  const double vx = first ? v1.x() : v2.x(), vy = first ? v1.y() : v2.y();
  const double norm = std::sqrt(vx * vx + vy * vy);
  return norm > 0 ? Eigen::Vector2d(vx / norm, vy / norm) : Eigen::Vector2d::Zero();
}

}  // namespace

Eigen::Vector2d FitNormal(const Eigen::Vector2d* points, int count) { return FitNormalInline(points, count); }

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
  t.full_circle = full_circle;
  t.inverse_increment = 1.0 / geometry.angle_increment_rad;
  // Beam index padded by kBeamPad each side: wrapped for a full circle, -1 outside otherwise.
  constexpr int kPad = IcpTarget::kBeamPad;
  t.beam_lookup.assign(static_cast<size_t>(beams + 2 * kPad), -1);
  t.beam_points.resize(t.beam_lookup.size());
  for (int b = -kPad; b < beams + kPad; ++b) {
    int wrapped = b;
    while (full_circle && wrapped < 0) wrapped += beams;
    while (full_circle && wrapped >= beams) wrapped -= beams;
    const int j = wrapped >= 0 && wrapped < beams ? t.point_of_beam[static_cast<size_t>(wrapped)] : -1;
    t.beam_lookup[static_cast<size_t>(b + kPad)] = j;
    t.beam_points[static_cast<size_t>(b + kPad)] =
        j >= 0 ? t.points[static_cast<size_t>(j)] : Eigen::Vector2d(IcpTarget::kNoPoint, IcpTarget::kNoPoint);
  }
  // The point on beam b (b within kPad of the scan from the padded index, else wrapped), -1 if none.
  auto point_on_beam = [&](int b) {
    if (b >= -kPad && b < beams + kPad) return t.beam_lookup[static_cast<size_t>(b + kPad)];
    if (full_circle) b = ((b % beams) + beams) % beams;
    return b >= 0 && b < beams ? t.point_of_beam[static_cast<size_t>(b)] : -1;
  };
  t.normals.assign(static_cast<size_t>(n), Eigen::Vector2d::Zero());
  std::vector<Eigen::Vector2d> nb(static_cast<size_t>(2 * config.normal_half_window + 1));
  for (int k = 0; k < n; ++k) {
    int count = 0;
    const int b0 = sp.beam[static_cast<size_t>(k)];
    const Eigen::Vector2d& p = t.points[static_cast<size_t>(k)];
    for (int db = -config.normal_half_window; db <= config.normal_half_window; ++db) {
      const int j = point_on_beam(b0 + db);
      if (j >= 0 && (t.points[static_cast<size_t>(j)] - p).squaredNorm() <= max2)
        nb[static_cast<size_t>(count++)] = t.points[static_cast<size_t>(j)];
    }
    if (count >= 3) t.normals[static_cast<size_t>(k)] = FitNormalInline(nb.data(), count);
  }
  t.kd_tree = std::make_shared<LazyKdTree>();
  if (config.build_kd_tree) t.kd_tree->Get(t.points);
  return t;
}

IcpTarget SubsetTarget(const IcpTarget& cloud, const std::vector<int>& indices) {
  IcpTarget t;
  t.points.reserve(indices.size());
  t.normals.reserve(indices.size());
  for (int i : indices) t.points.push_back(cloud.points[i]), t.normals.push_back(cloud.normals[i]);
  t.kd_tree = std::make_shared<LazyKdTree>();
  return t;
}

IcpTarget MakeCloudTarget(std::vector<Eigen::Vector2d> points, const IcpTargetConfig& config) {
  IcpTarget t;
  t.points = std::move(points);
  t.kd_tree = std::make_shared<LazyKdTree>();
  const KdTree2d& tree = t.kd_tree->Get(t.points);
  const size_t k = static_cast<size_t>(std::max(config.normal_neighbors, 1));
  const double max2 = config.normal_max_neighbor_m * config.normal_max_neighbor_m;
  std::vector<std::uint32_t> idx(k);
  std::vector<double> d2(k);
  std::vector<Eigen::Vector2d> nb;
  t.normals.assign(t.points.size(), Eigen::Vector2d::Zero());
  for (size_t i = 0; i < t.points.size(); ++i) {
    const size_t found = tree.tree.knnSearch(t.points[i].data(), k, idx.data(), d2.data());
    nb.clear();
    for (size_t m = 0; m < found; ++m)
      if (d2[m] <= max2) nb.push_back(t.points[idx[m]]);
    if (nb.size() >= 3) t.normals[i] = FitNormal(nb.data(), static_cast<int>(nb.size()));
  }
  return t;
}

namespace {
// NearestOnBeamsBatch with the window a compile-time constant, so that the search unrolls;
// same result (first strict minimum in beam order, kNoPoint beams lose). A window
// reaching past the padded index takes NearestOnBeams' clamped path.
template <int kWindow>
void NearestOnBeamsAll(const IcpTarget& target, const Eigen::Vector2d* q, const double* bearing, size_t n,
                       int* nearest, double* dist2) {
  constexpr int kPad = IcpTarget::kBeamPad;
  const int beams = static_cast<int>(target.point_of_beam.size());
  const Eigen::Vector2d* beam_points = target.beam_points.data() + kPad;
  const int* lookup = target.beam_lookup.data() + kPad;
  for (size_t i = 0; i < n; ++i) {
    const int center = CenterBeam(target, bearing[i]);
    if (center - kWindow < -kPad || center + kWindow >= beams + kPad) {
      if (!NearestOnBeams(target, q[i], bearing[i], kWindow, &nearest[i], &dist2[i])) nearest[i] = -1;
      continue;
    }
    double best = std::numeric_limits<double>::infinity();
    int best_b = center - kWindow;
    for (int b = center - kWindow; b <= center + kWindow; ++b) {
      const double d2 = (beam_points[b] - q[i]).squaredNorm();
      const bool closer = d2 < best;
      best = closer ? d2 : best;
      best_b = closer ? b : best_b;
    }
    nearest[i] = lookup[best_b];
    dist2[i] = best;
  }
}

}  // namespace

void NearestOnBeamsBatch(const IcpTarget& target, const Eigen::Vector2d* q, const double* bearing_rad, size_t n,
                         int window_beams, int* nearest, double* dist2_m2) {
  switch (window_beams) {
    case 0: return NearestOnBeamsAll<0>(target, q, bearing_rad, n, nearest, dist2_m2);
    case 1: return NearestOnBeamsAll<1>(target, q, bearing_rad, n, nearest, dist2_m2);
    case 2: return NearestOnBeamsAll<2>(target, q, bearing_rad, n, nearest, dist2_m2);
    default:
      for (size_t i = 0; i < n; ++i)
        if (!NearestOnBeams(target, q[i], bearing_rad[i], window_beams, &nearest[i], &dist2_m2[i])) nearest[i] = -1;
  }
}

bool NearestByKdTree(const IcpTarget& target, const Eigen::Vector2d& q, int* index, double* dist2_m2) {
  assert(target.kd_tree && "IcpTarget built without a kd-tree");
  if (target.points.empty()) return false;
  std::uint32_t i = 0;
  double d2 = 0;
  if (target.kd_tree->Get(target.points).tree.knnSearch(q.data(), 1, &i, &d2) == 0) return false;
  *index = static_cast<int>(i);
  *dist2_m2 = d2;
  return true;
}

}  // namespace slambox
