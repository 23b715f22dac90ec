#pragma once
// Boundaries of the occupied cells of an occupancy grid as closed polygons: what Box2D's
// chain loops need so the robot collides with a world given as a map image (a loop is
// one-sided in Box2D 2.4, its normal to the right of each edge: here the free side), and
// the wall segments a localization module's map is made of.
// Every cell side between an occupied cell and a free one (or the grid's outside) is a
// directed unit edge with the occupied cell on its left; edges are chained into loops,
// turning left where cells touch only at a corner (diagonal neighbours are not joined;
// a loop may touch itself at such a vertex, never cross), and collinear runs are merged. Outer boundaries come
// out counter-clockwise, holes clockwise.
#include <Eigen/Core>
#include <vector>

#include "core/estimate.hpp"

namespace slambox {

using Contour = std::vector<Eigen::Vector2d>;  ///< [m] world frame, closed (last -> first implied)

/// Loops around the cells whose value > occupied_above (unknown and free are outside).
std::vector<Contour> OccupiedContours(const OccupancyGrid& grid, int occupied_above = 50);

/// Signed area [m^2] (> 0 counter-clockwise), shoelace formula.
double ContourArea(const Contour& contour);

}  // namespace slambox
