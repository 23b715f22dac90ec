#pragma once
// The reference ("target") side of ICP: points with unit normals and two ways to find a
// point's correspondence — a kd-tree (nanoflann, any cloud) and projection into the
// reference scan's beam index (constant time, only for a single scan in its own frame).
#include <Eigen/Core>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "core/stream.hpp"
#include "slam/scan_points.hpp"

namespace slambox {

struct KdTree2d;  // nanoflann index over a private copy of the points (icp_target.cpp)

struct IcpTarget {
  std::vector<Eigen::Vector2d> points;   ///< [m] target frame
  std::vector<Eigen::Vector2d> normals;  ///< unit normals; (0, 0) where too few neighbours
  std::shared_ptr<const KdTree2d> kd_tree;  ///< null unless built
  // Projection model: beam b of the reference scan looks along angle_min + b * increment.
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
  std::vector<int> point_of_beam;  ///< point index per beam, -1 without a point; empty = no model
  /// point_of_beam padded with kBeamPad beams each side (wrapped for a full circle, -1
  /// otherwise), so a window search needs no modulo.
  static constexpr int kBeamPad = 16;
  std::vector<int> beam_lookup;
  double inverse_increment = 0.0;  ///< [1/rad]
  bool full_circle = false;
};

struct IcpTargetConfig {
  int normal_half_window = 2;          ///< neighbours on each side (beams or kNN/2) in the normal fit
  double normal_max_neighbor_m = 0.3;  ///< [m] neighbours farther from the point are not on its surface
  bool build_kd_tree = true;           ///< false saves time when only projection is used
};

/// A single scan in its robot frame: normals by PCA over neighbouring beams, beam index,
/// and a kd-tree when asked.
IcpTarget MakeScanTarget(const ScanPoints& scan_points, const LaserScanEvent& geometry,
                         const IcpTargetConfig& config = {});
/// Any cloud (e.g. a local map): kd-tree always, normals by PCA over the k nearest.
IcpTarget MakeCloudTarget(std::vector<Eigen::Vector2d> points, const IcpTargetConfig& config = {});

/// Nearest target point to q (target frame). False when the target is empty.
bool NearestByKdTree(const IcpTarget& target, const Eigen::Vector2d& q, int* index, double* dist2_m2);
/// Unit normal of a 2D point set by PCA: the eigenvector of the smaller eigenvalue of the
/// scatter matrix (closed form for 2x2). (0, 0) for fewer than 2 distinct points.
Eigen::Vector2d FitNormal(const Eigen::Vector2d* points, int count);

/// atan2 with |error| <= 1e-5 rad (Abramowitz & Stegun 4.4.49); enough to pick a beam.
/// Branch-free so that loops over it vectorize.
inline double FastAtan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double mx = std::max(ax, ay), mn = std::min(ax, ay);
  const double a = mn / (mx + 1e-300), a2 = a * a;
  double r = a * (0.9998660 + a2 * (-0.3302995 + a2 * (0.1801410 + a2 * (-0.0851330 + a2 * 0.0208351))));
  r = ay > ax ? M_PI_2 - r : r;
  r = x < 0 ? M_PI - r : r;
  return y < 0 ? -r : r;
}

/// The nearest among the target points on beams within +-window_beams (<= kBeamPad) of
/// bearing_rad, q's bearing in the target frame. False when none of those beams has a
/// point. Inline: ICP's inner loop.
inline bool NearestOnBeams(const IcpTarget& target, const Eigen::Vector2d& q, double bearing_rad, int window_beams,
                           int* index, double* dist2_m2) {
  const int beams = static_cast<int>(target.point_of_beam.size());
  assert(beams > 0 && "IcpTarget has no beam index (not built from a scan)");
  assert(window_beams <= IcpTarget::kBeamPad);
  double f = (bearing_rad - target.angle_min_rad) * target.inverse_increment;
  if (target.full_circle) {
    if (f < -0.5) f += beams;
    else if (f >= beams - 0.5) f -= beams;
  }
  const int center = static_cast<int>(std::floor(f + 0.5));
  const int lo = std::max(center - window_beams, -IcpTarget::kBeamPad);
  const int hi = std::min(center + window_beams, beams + IcpTarget::kBeamPad - 1);
  const int* lookup = target.beam_lookup.data() + IcpTarget::kBeamPad;
  double best = std::numeric_limits<double>::infinity();
  int best_i = -1;
  for (int b = lo; b <= hi; ++b) {
    const int j = lookup[b];
    if (j < 0) continue;
    const double d2 = (target.points[static_cast<size_t>(j)] - q).squaredNorm();
    if (d2 < best) best = d2, best_i = j;
  }
  if (best_i < 0) return false;
  *index = best_i;
  *dist2_m2 = best;
  return true;
}

/// NearestOnBeams at q's own bearing.
inline bool NearestByProjection(const IcpTarget& target, const Eigen::Vector2d& q, int window_beams, int* index,
                                double* dist2_m2) {
  return NearestOnBeams(target, q, FastAtan2(q.y(), q.x()), window_beams, index, dist2_m2);
}

}  // namespace slambox
