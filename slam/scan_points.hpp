#pragma once
// LaserScanEvent -> 2D points in the robot frame (the LIDAR sits at the robot's origin,
// as the simulator mounts it). Only valid beams become points; optional range limits and
// voxel subsampling thin the cloud for ICP and maps.
#include <Eigen/Core>
#include <vector>

#include "core/stream.hpp"

namespace slambox {

struct ScanPointsConfig {
  double range_min_m = 0.0;   ///< [m] drop closer returns (0 = the scan's own range_min_m)
  double range_max_m = 0.0;   ///< [m] drop farther returns (0 = keep up to the scan's range_max_m)
  double voxel_size_m = 0.0;  ///< [m] keep one point per square voxel (VoxelSubsample; 0 = off)
};

/// Points of one scan with the beam each came from (for projection correspondences and
/// normals from neighbouring beams).
struct ScanPoints {
  std::vector<Eigen::Vector2d> points;  ///< [m] robot frame
  std::vector<int> beam;                ///< beam index of each point
};

ScanPoints ScanToPoints(const LaserScanEvent& scan, const ScanPointsConfig& config = {});

/// Keeps, of the points in each voxel_size_m square, the one nearest their centroid (ties:
/// the earlier), whatever order they come in; voxels in order of first arrival
/// (deterministic). Returns the kept indices.
std::vector<int> VoxelSubsample(const std::vector<Eigen::Vector2d>& points, double voxel_size_m);

}  // namespace slambox
