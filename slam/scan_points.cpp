#include "slam/scan_points.hpp"

#include <cmath>
#include <unordered_set>

namespace slambox {

ScanPoints ScanToPoints(const LaserScanEvent& scan, const ScanPointsConfig& config) {
  const double r_min = config.range_min_m > 0 ? config.range_min_m : scan.range_min_m;
  const double r_max = config.range_max_m > 0 ? config.range_max_m : scan.range_max_m;
  ScanPoints out;
  out.points.reserve(scan.ranges_m.size());
  out.beam.reserve(scan.ranges_m.size());
  for (size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double r = scan.ranges_m[i];
    if (!scan.valid[i] || !std::isfinite(r) || r < r_min || r > r_max) continue;
    const double a = scan.angle_min_rad + static_cast<double>(i) * scan.angle_increment_rad;
    out.points.emplace_back(r * std::cos(a), r * std::sin(a));
    out.beam.push_back(static_cast<int>(i));
  }
  if (config.voxel_size_m > 0) {
    ScanPoints thin;
    for (int k : VoxelSubsample(out.points, config.voxel_size_m)) {
      thin.points.push_back(out.points[k]);
      thin.beam.push_back(out.beam[k]);
    }
    return thin;
  }
  return out;
}

std::vector<int> VoxelSubsample(const std::vector<Eigen::Vector2d>& points, double voxel_size_m) {
  std::vector<int> kept;
  std::unordered_set<std::uint64_t> occupied;
  occupied.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const auto ix = static_cast<std::int32_t>(std::floor(points[i].x() / voxel_size_m));
    const auto iy = static_cast<std::int32_t>(std::floor(points[i].y() / voxel_size_m));
    const std::uint64_t key = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ix)) << 32) |
                              static_cast<std::uint32_t>(iy);
    if (occupied.insert(key).second) kept.push_back(static_cast<int>(i));
  }
  return kept;
}

}  // namespace slambox
