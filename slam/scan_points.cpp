#include "slam/scan_points.hpp"

#include <cmath>
#include <unordered_map>
#include <vector>

namespace slambox {
namespace {

// cos / sin of every beam angle, angle_min + i * increment, for the last scan geometry
// seen on this thread (a LIDAR's geometry never changes, so this is computed once). Same
// expressions as a direct evaluation, so the points are bit-identical.
struct BeamDirections {
  double angle_min_rad = 0.0, angle_increment_rad = 0.0;
  std::vector<double> cos, sin;
};

const BeamDirections& DirectionsFor(const LaserScanEvent& scan) {
  thread_local BeamDirections d;
  if (d.cos.size() != scan.ranges_m.size() || d.angle_min_rad != scan.angle_min_rad ||
      d.angle_increment_rad != scan.angle_increment_rad) {
    d.angle_min_rad = scan.angle_min_rad;
    d.angle_increment_rad = scan.angle_increment_rad;
    d.cos.resize(scan.ranges_m.size());
    d.sin.resize(scan.ranges_m.size());
    for (size_t i = 0; i < scan.ranges_m.size(); ++i) {
      const double a = scan.angle_min_rad + static_cast<double>(i) * scan.angle_increment_rad;
      d.cos[i] = std::cos(a);
      d.sin[i] = std::sin(a);
    }
  }
  return d;
}

}  // namespace

ScanPoints ScanToPoints(const LaserScanEvent& scan, const ScanPointsConfig& config) {
  const double r_min = config.range_min_m > 0 ? config.range_min_m : scan.range_min_m;
  const double r_max = config.range_max_m > 0 ? config.range_max_m : scan.range_max_m;
  const BeamDirections& dir = DirectionsFor(scan);
  ScanPoints out;
  out.points.reserve(scan.ranges_m.size());
  out.beam.reserve(scan.ranges_m.size());
  for (size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double r = scan.ranges_m[i];
    if (!scan.valid[i] || !std::isfinite(r) || r < r_min || r > r_max) continue;
    out.points.emplace_back(r * dir.cos[i], r * dir.sin[i]);
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
  // Which point stands for a voxel must not depend on the input order: with the first one
  // kept, a scan's beam order picks, along a wall, the beam whose range noise pushed its
  // point into the voxel from the side the sweep came from, so the kept points lean off
  // the wall by an amount that changes with the incidence angle and the thinned wall turns
  // (a 180-degree scanner in a corridor drifted by ~0.05 deg/m through a local map built so).
  // The point nearest the voxel's centroid is kept instead: the centroid of the points that
  // fell in is unbiased, and the kept point is still a measured one.
  struct Voxel {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    int count = 0;
    int best = -1;
    double best_d2 = 0.0;
  };
  std::unordered_map<std::uint64_t, int> slot_of;
  slot_of.reserve(points.size());
  std::vector<Voxel> voxels;
  std::vector<int> slot(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const auto ix = static_cast<std::int32_t>(std::floor(points[i].x() / voxel_size_m));
    const auto iy = static_cast<std::int32_t>(std::floor(points[i].y() / voxel_size_m));
    const std::uint64_t key = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ix)) << 32) |
                              static_cast<std::uint32_t>(iy);
    const auto [it, inserted] = slot_of.emplace(key, static_cast<int>(voxels.size()));
    if (inserted) voxels.emplace_back();
    Voxel& v = voxels[static_cast<size_t>(it->second)];
    v.sum += points[i];
    ++v.count;
    slot[i] = it->second;
  }
  for (size_t i = 0; i < points.size(); ++i) {
    Voxel& v = voxels[static_cast<size_t>(slot[i])];
    const double d2 = (points[i] - v.sum / v.count).squaredNorm();
    if (v.best < 0 || d2 < v.best_d2) {
      v.best = static_cast<int>(i);
      v.best_d2 = d2;
    }
  }
  std::vector<int> kept;
  kept.reserve(voxels.size());
  for (const Voxel& v : voxels) kept.push_back(v.best);
  return kept;
}

}  // namespace slambox
