#pragma once
// Exact ray casting against an occupancy grid (a world given as a map image): the range
// to the first occupied cell the ray enters, walking the cells it crosses in order
// (Amanatides & Woo, "A Fast Voxel Traversal Algorithm", Eurographics 1987). Cells are
// the half-open squares origin + [ix, ix+1) x [iy, iy+1) * resolution; a cell is occupied
// when its value > occupied_above (unknown and free cells let the beam pass). A ray
// that starts inside an occupied cell hits at 0, like a two-sided edge at t = 0.
// Each crossing parameter is computed from its cell boundary directly (no running sums),
// with the same arithmetic as the per-cell slab test of the brute-force oracle.
#include <Eigen/Core>

#include "core/estimate.hpp"

namespace slambox {

struct GridRayCaster {
  const OccupancyGrid* grid = nullptr;
  int occupied_above = 50;  ///< a cell value > this blocks the beam (GridMapOptions' threshold)
};

/// Range [m] along the unit direction `dir` to the entry point of the first occupied cell
/// within max_range_m, or +inf (sim/ray_caster.hpp's kNoHit).
double CastGridRay(const GridRayCaster& caster, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                   double max_range_m);

/// The oracle: the minimum entry range over every occupied cell (slab test per cell).
double CastGridRayBruteForce(const GridRayCaster& caster, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                             double max_range_m);

}  // namespace slambox
