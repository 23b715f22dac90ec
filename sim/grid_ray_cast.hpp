#pragma once
// Exact ray casting against an occupancy grid (a world given as a map image): the range
// to the first occupied cell the ray enters, walking the cells it crosses in order
// (Amanatides & Woo, "A Fast Voxel Traversal Algorithm", Eurographics 1987). Cells are
// the half-open squares origin + [ix, ix+1) x [iy, iy+1) * resolution; a cell is occupied
// when its value > occupied_above (unknown and free cells let the beam pass). A ray
// that starts inside an occupied cell hits at 0, like a two-sided edge at t = 0.
// Two levels: the walk steps over blocks of kBlock x kBlock cells that hold no occupied
// cell and walks cell by cell only inside the others. Each crossing parameter is
// computed from its grid line directly (no running sums), with the arithmetic of the
// per-cell slab test of the brute-force oracle, so both agree to rounding.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/estimate.hpp"

namespace slambox {

class GridRayCaster {
 public:
  static constexpr int kBlock = 8;  ///< cells per block side (0.4 m at 0.05 m; 8 and 16 measured alike, 32 slower)
  /// Keeps a pointer to `grid` (it must outlive the caster).
  explicit GridRayCaster(const OccupancyGrid& grid, int occupied_above = 50);
  /// Range [m] along the unit direction `dir` to the entry point of the first occupied
  /// cell within max_range_m, or +inf (sim/ray_caster.hpp's kNoHit).
  double Cast(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m) const;
  /// The oracle: the minimum entry range over every occupied cell (slab test per cell).
  double CastBruteForce(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m) const;

 private:
  bool Occupied(int ix, int iy) const { return occupied_[static_cast<std::size_t>(iy) * width_ + ix] != 0; }
  const OccupancyGrid* grid_;
  int width_ = 0, height_ = 0, blocks_x_ = 0, blocks_y_ = 0;
  std::vector<std::uint8_t> occupied_;        ///< per cell
  std::vector<std::uint8_t> block_occupied_;  ///< per block: any occupied cell
};

}  // namespace slambox
