#include "slam/loop_region.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slambox {

std::vector<RegionPass> SplitIntoPasses(const std::vector<int>& sorted_members) {
  std::vector<RegionPass> passes;
  for (int i : sorted_members) {
    if (!passes.empty() && passes.back().last + 1 == i) passes.back().last = i;
    else passes.push_back({i, i});
  }
  return passes;
}

void PointHashGrid::Insert(const Eigen::Vector2d& p) {
  const long long x = static_cast<long long>(std::floor(p.x() / cell_m_));
  const long long y = static_cast<long long>(std::floor(p.y() / cell_m_));
  cells_[Key(x, y)].push_back(static_cast<int>(points_.size()));
  points_.push_back(p);
}

double PointHashGrid::NearestWithinCell(const Eigen::Vector2d& q) const {
  const long long cx = static_cast<long long>(std::floor(q.x() / cell_m_));
  const long long cy = static_cast<long long>(std::floor(q.y() / cell_m_));
  double best2 = cell_m_ * cell_m_;
  bool found = false;
  for (long long dy = -1; dy <= 1; ++dy)
    for (long long dx = -1; dx <= 1; ++dx) {
      const auto it = cells_.find(Key(cx + dx, cy + dy));
      if (it == cells_.end()) continue;
      for (int i : it->second) {
        const double d2 = (points_[static_cast<size_t>(i)] - q).squaredNorm();
        if (d2 <= best2) {
          best2 = d2;
          found = true;
        }
      }
    }
  return found ? std::sqrt(best2) : std::numeric_limits<double>::infinity();
}

PassAgreement MeasureAgreement(const PointHashGrid& grid, const std::vector<Eigen::Vector2d>& pass_points,
                               const RegionConfig& config) {
  PassAgreement a;
  double sum = 0.0;
  const double inv2s2 = 1.0 / (2.0 * config.sigma_m * config.sigma_m);
  for (const auto& q : pass_points) {
    ++a.points;
    const double d = grid.NearestWithinCell(q);
    if (d > config.overlap_m) continue;
    ++a.overlap;
    sum += std::exp(-d * d * inv2s2);
  }
  a.score = a.overlap > 0 ? sum / a.overlap : 0.0;
  a.admitted = a.overlap >= config.min_overlap_fraction * a.points && a.score >= config.min_agreement;
  return a;
}

RegionSelection SelectConsistentPasses(const std::vector<SE2>& poses,
                                       const std::vector<const std::vector<Eigen::Vector2d>*>& points_of,
                                       const std::vector<int>& members, int anchor,
                                       const Eigen::Vector2d& query_position, const RegionConfig& config) {
  RegionSelection out;
  std::vector<RegionPass> passes = SplitIntoPasses(members);
  // Order: the anchor's pass, then by the distance of the pass's nearest keyframe.
  std::vector<double> nearest(passes.size(), std::numeric_limits<double>::infinity());
  for (size_t p = 0; p < passes.size(); ++p) {
    for (int i = passes[p].first; i <= passes[p].last; ++i)
      nearest[p] = std::min(nearest[p], (poses[static_cast<size_t>(i)].translation() - query_position).norm());
    if (anchor >= passes[p].first && anchor <= passes[p].last) nearest[p] = -1.0;
  }
  std::vector<size_t> order(passes.size());
  for (size_t p = 0; p < order.size(); ++p) order[p] = p;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return nearest[a] < nearest[b]; });
  PointHashGrid grid(config.overlap_m);
  std::vector<Eigen::Vector2d> world;
  for (size_t n = 0; n < order.size(); ++n) {
    const RegionPass& pass = passes[order[n]];
    world.clear();
    for (int i = pass.first; i <= pass.last; ++i) {
      const SE2& T = poses[static_cast<size_t>(i)];
      for (const auto& p : *points_of[static_cast<size_t>(i)]) world.push_back(T * p);
    }
    PassAgreement a;
    if (n == 0) {  // the anchor's pass founds the union
      a.points = static_cast<int>(world.size());
      a.admitted = true;
    } else {
      a = MeasureAgreement(grid, world, config);
    }
    out.passes.push_back(pass);
    out.agreement.push_back(a);
    if (!a.admitted) continue;
    ++out.admitted_passes;
    for (const auto& p : world) grid.Insert(p);
    for (int i = pass.first; i <= pass.last; ++i) out.keyframes.push_back(i);
  }
  std::sort(out.keyframes.begin(), out.keyframes.end());
  return out;
}

}  // namespace slambox
