#pragma once
// The reference ("target") side of ICP: points with unit normals and two ways to find a
// point's correspondence — a kd-tree (nanoflann, any cloud) and projection into the
// reference scan's beam index (constant time, only for a single scan in its own frame).
#include <Eigen/Core>
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
/// The nearest among the target points on beams within +-window_beams of q's bearing.
/// False when none of those beams has a point.
bool NearestByProjection(const IcpTarget& target, const Eigen::Vector2d& q, int window_beams, int* index,
                         double* dist2_m2);

/// Unit normal of a 2D point set by PCA: the eigenvector of the smaller eigenvalue of the
/// scatter matrix (closed form for 2x2). (0, 0) for fewer than 2 distinct points.
Eigen::Vector2d FitNormal(const Eigen::Vector2d* points, int count);

}  // namespace slambox
