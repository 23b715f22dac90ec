#pragma once
// Correlative scan matching (Olson 2009) with Cartographer's branch-and-bound search (Hess
// et al. 2016, Sec. V): a global match of a scan against a point map inside a search
// window, without a good initial guess.
//   score table:  per cell of a grid over the map, exp(-d^2 / (2 sigma^2)) with d the
//                 distance from the cell centre to the nearest map point (0 beyond 3 sigma);
//   score:        the mean table value over the source points' cells; optionally a cell the
//                 map never observed (no ray from a map point's viewpoint crossed it, or past
//                 the table's edge) is worth unknown_score instead of 0;
//   search:       every rotation in the angular window (step from the scan's extent), every
//                 translation on the grid in the linear window; depth-first branch-and-bound
//                 over translations with precomputed max-pooled tables (level h: the max over
//                 2^h x 2^h cells), which bound every child's score from above, so the result
//                 is the exhaustive optimum.
#include <Eigen/Core>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct ScoreTableConfig {
  double resolution_m = 0.05;  ///< [m] cell size (the translation step of the search)
  double sigma_m = 0.05;       ///< [m] std of the point-to-map distance in the score
  int levels = 5;              ///< max-pooled tables for branch-and-bound (level 0 = the table)
  /// Value of a cell the map never observed (no ray of it crossed the cell, no point near it);
  /// 0 = such a cell scores as free space (needs no viewpoints).
  double unknown_score = 0.0;
};

/// Score table over a map in its own frame, with its max-pooled levels.
struct ScoreTable {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  ///< [m] lower corner of cell (0, 0)
  double resolution_m = 0.05;
  int width = 0, height = 0;
  /// levels[h][y * width + x] = max of levels[0] over cells [x, x + 2^h) x [y, y + 2^h).
  std::vector<std::vector<float>> levels;
  /// Value of every cell past the table's edge (the map's box plus its margin): unknown_score,
  /// even where a ray from a viewpoint outside the box crossed it.
  float outside = 0.0f;
  /// Level-h value at cell (x, y); `outside` outside the table.
  float At(int h, int x, int y) const {
    if (x < 0 || y < 0 || x >= width || y >= height) return outside;
    return levels[static_cast<size_t>(h)][static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
  }
  /// Cell of a point: floor((p - origin) / resolution).
  Eigen::Vector2i Cell(const Eigen::Vector2d& p) const;
};

/// Table over map points (map frame). The table extends past the points by 3 sigma plus
/// 2^(levels-1) cells, so pooled values next to the border stay exact upper bounds.
/// viewpoints[i]: where map_points[i] was seen from (needed when config.unknown_score > 0: the
/// cells on the segment from it to the point are observed).
ScoreTable MakeScoreTable(const std::vector<Eigen::Vector2d>& map_points, const ScoreTableConfig& config = {},
                          const std::vector<Eigen::Vector2d>& viewpoints = {});

/// Mean level-0 value over the source points' cells, the source placed at T_map_source.
double CorrelativeScore(const ScoreTable& table, const std::vector<Eigen::Vector2d>& source, const SE2& T_map_source);

struct CorrelativeSearchConfig {
  double linear_window_m = 2.0;     ///< [m] search +-this in x and y around the guess
  double angular_window_deg = 30.0; ///< [deg] search +-this around the guess heading
  /// [deg] rotation step; 0 = Cartographer's: the step that moves the farthest source
  /// point (range capped at max_range_for_step_m) by one cell.
  double angular_step_deg = 0.0;
  double max_range_for_step_m = 10.0;  ///< [m] cap on the range that sets the automatic step
  double min_score = 0.0;              ///< candidates scoring below this are pruned
  /// [m] > 0: also find the best pose whose translation is farther than this from the
  /// best one (CorrelativeMatch::runner_up_score), a measure of ambiguity (a corridor,
  /// a symmetric room): a second branch-and-bound pass that skips leaves near the best.
  double runner_up_radius_m = 0.0;
};

struct CorrelativeMatch {
  bool found = false;  ///< a pose scored at least min_score
  SE2 T_map_source;    ///< best pose on the search lattice
  double score = 0.0;  ///< its CorrelativeScore
  int evaluated = 0;   ///< candidate scores computed (bounds and leaves), for cost reports
  /// Best score farther than runner_up_radius_m from T_map_source (0 when none or not asked).
  double runner_up_score = 0.0;
  /// The best pose lies on the window's boundary (outermost translation cell in x or y, or
  /// outermost rotation): the score still rises outwards there, so it is no local optimum and
  /// the true pose is likely outside the window.
  bool at_window_edge = false;
};

/// Branch-and-bound search: the exhaustive optimum's score over the lattice (between
/// exactly tied poses it may pick another than the exhaustive search).
CorrelativeMatch MatchCorrelative(const ScoreTable& table, const std::vector<Eigen::Vector2d>& source,
                                  const SE2& T_map_source_guess, const CorrelativeSearchConfig& config);

/// The same lattice scored exhaustively (reference for tests; slow).
CorrelativeMatch MatchCorrelativeExhaustive(const ScoreTable& table, const std::vector<Eigen::Vector2d>& source,
                                            const SE2& T_map_source_guess, const CorrelativeSearchConfig& config);

}  // namespace slambox
