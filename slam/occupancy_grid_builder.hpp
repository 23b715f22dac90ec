#pragma once
// Occupancy grid from scans at known poses: log-odds update along each beam (Thrun,
// Prob. Robotics, Table 9.1, with the inverse sensor model reduced to hit / pass-through),
// rays traced cell by cell (Amanatides & Woo 1987).
#include <vector>

#include "core/estimate.hpp"

namespace slambox {

struct OccupancyGridConfig {
  double resolution_m = 0.05;    ///< [m] cell size
  double log_odds_hit = 0.85;    ///< added to the cell a beam ends in
  double log_odds_miss = -0.4;   ///< added to each cell a beam passes through
  double log_odds_clamp = 5.0;   ///< |log-odds| limit (keeps the map revisable)
  double margin_m = 0.5;         ///< [m] border around the data
  int max_cells = 40'000'000;    ///< larger grids get a coarser resolution
};

/// `scans[i]` are hit points in the robot frame of `poses[i]` (T_world_robot). The sensor
/// sits at the robot origin. Cells never observed are -1; others 0 (free) .. 100 (occupied).
OccupancyGrid BuildOccupancyGrid(const std::vector<SE2>& poses,
                                 const std::vector<std::vector<Eigen::Vector2d>>& scans,
                                 const OccupancyGridConfig& config = {});

}  // namespace slambox
