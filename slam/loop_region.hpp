#pragma once
// Region loop search for ICP PoseSLAM: when no single-keyframe submap closes a loop at a new
// keyframe (a pass the other way, a scan that sees farther than one submap holds), the
// target is the union of every old keyframe around it, admitted pass by pass (a pass = a run
// of consecutive keyframes) only where the map itself says the passes agree under the
// current estimate:
//   agreement(P, U) = mean over P's points q in the overlap of exp(-d(q, U)^2 / 2 sigma^2),
//   overlap        = P's points with a point of U closer than overlap_m,
// i.e. the correlative score (Olson 2009; the loop matcher's score table, same sigma) that
// pass P gets against the admitted union U where both saw something, without moving it. A
// pass enters only if it overlaps U (at least min_overlap_fraction of its points) and scores
// at least min_agreement there: two passes that the estimate places apart by more than the
// score's sigma (a doubled wall, a pass turned by a few degrees) are not merged, so the
// target never holds a wall twice. The first pass admitted is the one holding the old
// keyframe nearest to the new one (the anchor), whose frame the target is expressed in.
#include <Eigen/Core>
#include <unordered_map>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct RegionConfig {
  double overlap_m = 0.5;             ///< [m] a pass point with a union point this close is in the overlap
  double min_overlap_fraction = 0.25; ///< a pass must overlap the union with this fraction of its points
  double min_agreement = 0.6;         ///< mean exp(-d^2/2 sigma^2) over the overlap a pass needs
  double sigma_m = 0.05;              ///< [m] the score's sigma (the loop score table's)
};

/// A run of consecutive keyframe indices [first, last].
struct RegionPass {
  int first = 0, last = 0;
};

/// Runs of consecutive indices in `sorted_members` (ascending).
std::vector<RegionPass> SplitIntoPasses(const std::vector<int>& sorted_members);

/// Points of the admitted union in a hash grid of overlap_m cells, for distance queries
/// within overlap_m (the 3 x 3 cells around a query hold every point that close).
class PointHashGrid {
 public:
  explicit PointHashGrid(double cell_m) : cell_m_(cell_m) {}
  void Insert(const Eigen::Vector2d& p);
  /// Distance from q to the nearest inserted point, or +inf when none lies within cell_m.
  double NearestWithinCell(const Eigen::Vector2d& q) const;
  size_t size() const { return points_.size(); }

 private:
  static long long Key(long long x, long long y) { return (x << 32) ^ (y & 0xffffffffLL); }
  double cell_m_;
  std::vector<Eigen::Vector2d> points_;
  std::unordered_map<long long, std::vector<int>> cells_;
};

struct PassAgreement {
  int points = 0;        ///< points of the pass tested
  int overlap = 0;       ///< of them, within overlap_m of the union
  double score = 0.0;    ///< mean exp(-d^2/2 sigma^2) over the overlap (0 without overlap)
  bool admitted = false;
};

/// Agreement of `pass_points` (world frame) with the union in `grid`.
PassAgreement MeasureAgreement(const PointHashGrid& grid, const std::vector<Eigen::Vector2d>& pass_points,
                               const RegionConfig& config);

struct RegionSelection {
  std::vector<int> keyframes;             ///< admitted keyframes, ascending
  std::vector<RegionPass> passes;         ///< every pass, in the order they were tested
  std::vector<PassAgreement> agreement;   ///< per pass (the anchor's pass: admitted, not measured)
  int admitted_passes = 0;
};

/// Admits the passes of `members` (sorted keyframe indices) greedily: first the pass holding
/// `anchor`, then the others by their nearest keyframe's distance to `query_position`, each
/// measured against the union admitted so far. points_of[i]: keyframe i's points in its own
/// frame; poses[i]: its estimated pose.
RegionSelection SelectConsistentPasses(const std::vector<SE2>& poses,
                                       const std::vector<const std::vector<Eigen::Vector2d>*>& points_of,
                                       const std::vector<int>& members, int anchor,
                                       const Eigen::Vector2d& query_position, const RegionConfig& config);

}  // namespace slambox
