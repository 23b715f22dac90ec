#pragma once
// Occupancy-grid accuracy against the ground-truth world. The world's wall segments and
// circle boundaries are rasterized on the estimate grid's own lattice (origin,
// resolution, size): a cell is truly occupied when a segment intersects its square or a
// circle's boundary passes through it. Then
//  - cell error: among cells the estimate knows (value >= 0), the fraction whose
//    occupied/free class differs from the truth;
//  - mean nearest-occupied distance: for every estimated occupied cell, the Euclidean
//    distance [m] to the nearest truly occupied cell (exact distance transform,
//    Felzenszwalb & Huttenlocher 2012), averaged; and the reverse direction (truth to
//    estimate), which penalizes missing walls.
#include <cstdint>
#include <vector>

#include "core/estimate.hpp"
#include "core/world.hpp"

namespace slambox {

struct GridMapOptions {
  int occupied_above = 50;  ///< a cell value > this is occupied, 0..this is free, < 0 unknown
};

struct GridMapResult {
  int known_cells = 0;
  int estimated_occupied = 0;
  int true_occupied = 0;
  double cell_error = 0.0;                  ///< fraction in [0, 1]; NaN with no known cell
  double mean_nearest_occupied_m = 0.0;     ///< estimate -> truth; NaN if either has none
  double mean_truth_to_estimate_m = 0.0;    ///< truth -> estimate; NaN if either has none
};

/// 1 where the world's walls occupy a cell of the lattice of `grid` (its cells ignored).
std::vector<std::uint8_t> RasterizeWorld(const World& world, const OccupancyGrid& grid);

/// The world's walls as a grid on a lattice covering WorldBounds + `margin_m`: 100 where
/// RasterizeWorld marks a cell, 0 (free) elsewhere; empty (0 x 0) for a world without walls.
/// Written as maps/groundtruth.yaml beside the estimated maps.
OccupancyGrid TrueOccupancyGrid(const World& world, double resolution_m = 0.05, double margin_m = 0.5);

/// Exact Euclidean distance [cells] from every cell to the nearest cell with mask 1;
/// +inf everywhere when the mask is empty.
std::vector<double> DistanceTransform(const std::vector<std::uint8_t>& mask, int width, int height);

GridMapResult EvaluateGridMap(const OccupancyGrid& grid, const World& world, const GridMapOptions& options = {});

}  // namespace slambox
