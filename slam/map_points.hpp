#pragma once
// A known map as a point cloud: the world's walls and posts sampled along their outlines
// (for localization against the map; movers are not part of it).
#include <Eigen/Core>
#include <vector>

#include "core/world.hpp"

namespace slambox {

/// Points every `spacing_m` along every wall segment (both ends included) and around
/// every wall circle. Empty for a world without walls.
std::vector<Eigen::Vector2d> SampleWorldOutlines(const World& world, double spacing_m);

}  // namespace slambox
