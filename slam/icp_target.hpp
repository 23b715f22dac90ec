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

#include "core/fast_atan2.hpp"
#include "core/stream.hpp"
#include "slam/scan_points.hpp"

namespace slambox {

struct LazyKdTree;  // nanoflann index over a private copy of the points, built once (icp_target.cpp)

struct IcpTarget {
  std::vector<Eigen::Vector2d> points;   ///< [m] target frame
  std::vector<Eigen::Vector2d> normals;  ///< unit normals; (0, 0) where too few neighbours
  /// kd-tree over `points`: built by Make*Target when asked, else by the first
  /// NearestByKdTree (thread-safe). Copies share it, so points must not change afterwards.
  std::shared_ptr<LazyKdTree> kd_tree;
  // Projection model: beam b of the reference scan looks along angle_min + b * increment.
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
  std::vector<int> point_of_beam;  ///< point index per beam, -1 without a point; empty = no model
  /// point_of_beam padded with kBeamPad beams each side (wrapped for a full circle, -1
  /// otherwise), so a window search needs no modulo.
  static constexpr int kBeamPad = 16;
  std::vector<int> beam_lookup;
  /// The point of each beam_lookup entry, or kNoPoint where it is -1, so that a window
  /// search reads consecutive memory and has no branch.
  std::vector<Eigen::Vector2d> beam_points;
  static constexpr double kNoPoint = 1e150;  ///< [m] both coordinates: squared distance ~1e300, finite
  double inverse_increment = 0.0;  ///< [1/rad]
  bool full_circle = false;
};

struct IcpTargetConfig {
  int normal_half_window = 2;          ///< scans: beams on each side in the normal fit
  /// Clouds: the normal fit's k nearest (within normal_max_neighbor_m). Enough to span that
  /// radius at a local map's 5 cm voxels: k = 5 spans 0.2 m there, and with 3 cm range noise
  /// such a fit tilts by ~10 deg, which point-to-line reads as information along a featureless
  /// corridor (slam/README.md, "Normals from five neighbours").
  int normal_neighbors = 15;
  double normal_max_neighbor_m = 0.3;  ///< [m] neighbours farther from the point are not on its surface
  /// true: build the kd-tree now; false: on the first kd-tree query (projection never needs it)
  bool build_kd_tree = false;
};

/// A single scan in its robot frame: normals by PCA over neighbouring beams, beam index,
/// and a kd-tree (now when asked, else on first use).
IcpTarget MakeScanTarget(const ScanPoints& scan_points, const LaserScanEvent& geometry,
                         const IcpTargetConfig& config = {});
/// Any cloud (e.g. a local map): kd-tree always, normals by PCA over the k nearest.
IcpTarget MakeCloudTarget(std::vector<Eigen::Vector2d> points, const IcpTargetConfig& config = {});

/// The points `indices` of a cloud target with their normals; its own kd-tree, built on
/// the first query.
IcpTarget SubsetTarget(const IcpTarget& cloud, const std::vector<int>& indices);

/// Nearest target point to q (target frame). False when the target is empty.
bool NearestByKdTree(const IcpTarget& target, const Eigen::Vector2d& q, int* index, double* dist2_m2);
/// Unit normal of a 2D point set by PCA: the eigenvector of the smaller eigenvalue of the
/// scatter matrix (closed form for 2x2). (0, 0) for fewer than 2 distinct points.
Eigen::Vector2d FitNormal(const Eigen::Vector2d* points, int count);

/// The beam whose bearing is nearest to bearing_rad: floor((bearing - angle_min) /
/// increment + 1/2), wrapped into [0, beams) for a full circle; may lie outside the scan.
inline int CenterBeam(const IcpTarget& target, double bearing_rad) {
  const int beams = static_cast<int>(target.point_of_beam.size());
  double f = (bearing_rad - target.angle_min_rad) * target.inverse_increment;
  if (target.full_circle) {
    f += f < -0.5 ? beams : 0.0;
    f -= f >= beams - 0.5 ? beams : 0.0;
  }
  // floor without a library call or a branch; the clamp keeps the int conversion defined.
  const double g = std::clamp(f + 0.5, -1e9, 1e9);
  const int c = static_cast<int>(g);  // truncation: one too high for negative non-integers
  return c - (g < c ? 1 : 0);
}

/// The nearest among the target points on beams within +-window_beams (<= kBeamPad) of
/// bearing_rad, q's bearing in the target frame. False when none of those beams has a
/// point. Inline: ICP's inner loop.
inline bool NearestOnBeams(const IcpTarget& target, const Eigen::Vector2d& q, double bearing_rad, int window_beams,
                           int* index, double* dist2_m2) {
  const int beams = static_cast<int>(target.point_of_beam.size());
  assert(beams > 0 && "IcpTarget has no beam index (not built from a scan)");
  assert(window_beams <= IcpTarget::kBeamPad);
  const int center = CenterBeam(target, bearing_rad);
  const int lo = std::max(center - window_beams, -IcpTarget::kBeamPad);
  const int hi = std::min(center + window_beams, beams + IcpTarget::kBeamPad - 1);
  if (lo > hi) return false;
  const Eigen::Vector2d* beam_points = target.beam_points.data() + IcpTarget::kBeamPad;
  // First strict minimum in beam order; beams without a point are kNoPoint away, so they
  // lose to any real point and need no branch.
  double best = std::numeric_limits<double>::infinity();
  int best_b = lo;
  for (int b = lo; b <= hi; ++b) {
    const double d2 = (beam_points[b] - q).squaredNorm();
    const bool closer = d2 < best;
    best = closer ? d2 : best;
    best_b = closer ? b : best_b;
  }
  const int j = target.beam_lookup[static_cast<size_t>(best_b + IcpTarget::kBeamPad)];
  if (j < 0) return false;
  *index = j;
  *dist2_m2 = best;
  return true;
}

/// NearestOnBeams for n points at once: nearest[i] = -1 where none. Windows 0-2 run an
/// unrolled search with the same results (ICP's inner loop).
void NearestOnBeamsBatch(const IcpTarget& target, const Eigen::Vector2d* q, const double* bearing_rad, size_t n,
                         int window_beams, int* nearest, double* dist2_m2);

}  // namespace slambox
