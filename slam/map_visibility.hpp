#pragma once
// Which points of a known map a sensor could see from where it stands: a depth buffer over
// bearing bins, filled by the map's walls (segments and circles) as a ray caster would fill
// it, and a point counts as seen when it lies no farther than its bin's nearest wall plus a
// margin. A surface behind a wall is hidden: e.g. the outer edge of a map image's border,
// one wall thickness behind the inner wall, which scan-to-map ICP would otherwise pair a
// corridor's end wall with after the odometry drifted along the corridor
// (slam/README.md, "Map visibility in icp-localization").
#include <Eigen/Core>
#include <vector>

#include "core/world.hpp"

namespace slambox {

struct MapVisibilitySetting {
  double range_max_m = 30.0;         ///< [m] walls and points beyond are not considered
  double bin_rad = 0.25 * M_PI / 180.0;  ///< [rad] bearing resolution of the depth buffer
  /// [m] a point this far behind the nearest wall of its bin still counts as seen (points of
  /// a wall at grazing incidence spread over a bin's depth; the pose is only predicted)
  double depth_margin_m = 0.3;
};

/// Indices (ascending) of `points` seen from `origin` among the walls of `world`.
std::vector<int> VisibleMapPoints(const World& world, const std::vector<Eigen::Vector2d>& points,
                                  const Eigen::Vector2d& origin, const MapVisibilitySetting& setting);

}  // namespace slambox
