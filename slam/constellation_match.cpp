// Constellation matching (slam/constellation_match.hpp): hypotheses from pairs of equal
// length, support by nearest old landmark through a grid of cell tol, the union-bound test.
#include "slam/constellation_match.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "slam/icp_closed_form.hpp"
#include "slam/smoother_merges.hpp"

namespace slambox {

double BinomialUpperTail(int n, double p, int k) {
  if (k <= 0) return 1.0;
  if (k > n) return 0.0;
  if (!(p > 0.0)) return 0.0;
  if (!(p < 1.0)) return 1.0;
  double tail = 0.0;
  for (int i = k; i <= n; ++i)
    tail += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) + i * std::log(p) +
                     (n - i) * std::log1p(-p));
  return std::min(1.0, tail);
}

namespace {

/// The old landmarks in square cells of side tol: a point's neighbours within tol lie in
/// its cell and the eight around it.
class OldGrid {
 public:
  OldGrid(std::span<const Eigen::Vector2d> old, double cell_m) : old_(old), cell_m_(cell_m) {
    for (size_t i = 0; i < old.size(); ++i) cells_[Key(Cell(old[i]))].push_back(static_cast<int>(i));
  }
  bool AnyNear(const Eigen::Vector2d& p) const {
    bool any = false;
    ForEachNear(p, [&](int, double) { any = true; });
    return any;
  }
  /// Calls f(index, squared distance) for every old landmark within tol of p.
  template <typename F>
  void ForEachNear(const Eigen::Vector2d& p, F&& f) const {
    const auto [cx, cy] = Cell(p);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(Key({cx + dx, cy + dy}));
        if (it == cells_.end()) continue;
        for (const int i : it->second) {
          const double d2 = (old_[i] - p).squaredNorm();
          if (d2 <= cell_m_ * cell_m_) f(i, d2);
        }
      }
  }

 private:
  std::pair<long, long> Cell(const Eigen::Vector2d& p) const {
    return {static_cast<long>(std::floor(p.x() / cell_m_)), static_cast<long>(std::floor(p.y() / cell_m_))};
  }
  static long long Key(std::pair<long, long> c) { return (static_cast<long long>(c.first) << 32) ^ (c.second & 0xffffffffLL); }
  std::span<const Eigen::Vector2d> old_;
  double cell_m_;
  std::unordered_map<long long, std::vector<int>> cells_;
};

struct Support {
  std::vector<std::pair<int, int>> pairs;  // (old, recent)
  double sum_sq_m2 = 0.0;
};

/// The recent landmarks T brings within tol of an old one, each old one taken once, nearest first.
Support SupportOf(const SE2& T, std::span<const Eigen::Vector2d> recent, const OldGrid& grid) {
  std::vector<std::tuple<double, int, int>> near;  // (d^2, old, recent)
  for (size_t r = 0; r < recent.size(); ++r)
    grid.ForEachNear(T * recent[r], [&](int o, double d2) { near.emplace_back(d2, o, static_cast<int>(r)); });
  std::sort(near.begin(), near.end());
  Support s;
  std::vector<bool> old_used, recent_used(recent.size(), false);
  for (const auto& [d2, o, r] : near) {
    if (static_cast<size_t>(o) >= old_used.size()) old_used.resize(o + 1, false);
    if (old_used[o] || recent_used[r]) continue;
    old_used[o] = recent_used[r] = true;
    s.pairs.emplace_back(o, r);
    s.sum_sq_m2 += d2;
  }
  return s;
}

/// Least squares over the support, then its support again (kept if not smaller).
std::pair<SE2, Support> Refined(const SE2& T, Support s, std::span<const Eigen::Vector2d> old,
                                std::span<const Eigen::Vector2d> recent, const OldGrid& grid) {
  std::vector<Eigen::Vector2d> src, dst;
  for (const auto& [o, r] : s.pairs) src.push_back(recent[r]), dst.push_back(old[o]);
  const std::vector<double> w(src.size(), 1.0);
  const SE2 T_refined = AlignPointToPoint(src, dst, w);
  Support again = SupportOf(T_refined, recent, grid);
  if (again.pairs.size() >= s.pairs.size()) return {T_refined, std::move(again)};
  return {T, std::move(s)};
}

/// [m] how far motion T moves the anchor (the robot).
double AnchorShift(const SE2& T, const ConstellationSettings& settings) {
  return (T * settings.anchor_xy - settings.anchor_xy).norm();
}

struct OldPair {
  double length_m;
  int a, b;
};

}  // namespace

std::optional<ConstellationMatch> MatchConstellation(std::span<const Eigen::Vector2d> old,
                                                     std::span<const Eigen::Vector2d> recent,
                                                     const ConstellationSettings& settings, long* tried) {
  const double tol = settings.tolerance_m;
  const int n = static_cast<int>(recent.size());
  if (tried != nullptr) *tried = settings.earlier_hypotheses;
  if (n < 3 || old.size() < 3 || !(tol > 0)) return std::nullopt;
  Eigen::VectorXd stacked(2 * static_cast<long>(old.size()));
  for (size_t i = 0; i < old.size(); ++i) stacked.segment<2>(2 * static_cast<long>(i)) = old[i];
  const double p = 1.0 - std::exp(-MapDensity(stacked) * M_PI * tol * tol);

  // Old pairs by length, up to the longest recent pair (+ 2 tol). A pair shorter than 2 tol
  // fixes no direction (its rotation is uncertain by more than 30 degrees) and seeds nothing.
  double longest = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) longest = std::max(longest, (recent[i] - recent[j]).norm());
  std::vector<OldPair> old_pairs;
  for (size_t a = 0; a < old.size(); ++a)
    for (size_t b = a + 1; b < old.size(); ++b) {
      const double length = (old[a] - old[b]).norm();
      if (length > 2.0 * tol && length <= longest + 2.0 * tol) old_pairs.push_back({length, int(a), int(b)});
    }
  std::sort(old_pairs.begin(), old_pairs.end(), [](const OldPair& u, const OldPair& v) { return u.length_m < v.length_m; });

  auto length_range = [&](double length) {
    const auto first = std::lower_bound(old_pairs.begin(), old_pairs.end(), length - 2.0 * tol,
                                        [](const OldPair& u, double l) { return u.length_m < l; });
    const auto last = std::upper_bound(first, old_pairs.end(), length + 2.0 * tol,
                                       [](double l, const OldPair& u) { return l < u.length_m; });
    return std::pair{first, last};
  };
  // The hypotheses: i -> a, j -> b for every recent pair (i, j) and old pair (a, b) of the
  // same length, the rotation between their directions, then the midpoints; those turning by
  // more than max_rotation_rad are not hypotheses (and not counted in H).
  std::vector<SE2> seeds;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const Eigen::Vector2d d_recent = recent[j] - recent[i];
      const double length = d_recent.norm();
      if (length <= 2.0 * tol) continue;
      const auto [first, last] = length_range(length);
      for (auto it = first; it != last; ++it)
        for (const auto& [oa, ob] : {std::pair{it->a, it->b}, std::pair{it->b, it->a}}) {
          const Eigen::Vector2d d_old = old[ob] - old[oa];
          const double theta = NormalizeAngle(std::atan2(d_old.y(), d_old.x()) - std::atan2(d_recent.y(), d_recent.x()));
          if (std::abs(theta) > settings.max_rotation_rad) continue;
          const Eigen::Vector2d t = 0.5 * (old[oa] + old[ob]) - RotationMatrix(theta) * 0.5 * (recent[i] + recent[j]);
          if (AnchorShift(SE2(t.x(), t.y(), theta), settings) > settings.max_anchor_shift_m) continue;
          seeds.emplace_back(t.x(), t.y(), theta);
          if (settings.max_hypotheses > 0 && settings.earlier_hypotheses + static_cast<long>(seeds.size()) > settings.max_hypotheses) {
            if (tried != nullptr) *tried = settings.earlier_hypotheses + static_cast<long>(seeds.size());
            return std::nullopt;
          }
        }
    }
  const long total = settings.earlier_hypotheses + static_cast<long>(seeds.size());
  if (tried != nullptr) *tried = total;
  auto chance = [&](size_t k) {
    return std::min(1.0, static_cast<double>(total) * BinomialUpperTail(n - 2, p, static_cast<int>(k) - 2));
  };
  // The least support that passes; a hypothesis that cannot come within two of it (the
  // refinement may add one or two) is dropped before its support is counted.
  size_t k_pass = 3;
  while (k_pass <= static_cast<size_t>(n) && !(chance(k_pass) < settings.false_match_probability)) ++k_pass;
  if (k_pass > static_cast<size_t>(n)) return std::nullopt;
  const int k_floor = std::max(3, static_cast<int>(k_pass) - 2);

  const OldGrid grid(old, tol);
  struct Hypothesis {
    SE2 T;
    Support support;
  };
  std::vector<Hypothesis> kept;  // support >= k_floor, refined
  for (const SE2& T : seeds) {
    int misses = 0;
    for (int r = 0; r < n && misses <= n - k_floor; ++r) misses += grid.AnyNear(T * recent[r]) ? 0 : 1;
    if (misses > n - k_floor) continue;
    Support s = SupportOf(T, recent, grid);
    if (s.pairs.size() < static_cast<size_t>(k_floor)) continue;
    auto [T_refined, support] = Refined(T, std::move(s), old, recent, grid);
    if (std::abs(T_refined.theta) > settings.max_rotation_rad || AnchorShift(T_refined, settings) > settings.max_anchor_shift_m)
      continue;
    kept.push_back({T_refined, std::move(support)});
  }
  if (kept.empty()) return std::nullopt;

  const auto best = std::min_element(kept.begin(), kept.end(), [](const Hypothesis& u, const Hypothesis& v) {
    if (u.support.pairs.size() != v.support.pairs.size()) return u.support.pairs.size() > v.support.pairs.size();
    return u.support.sum_sq_m2 < v.support.sum_sq_m2;
  });
  if (!(chance(best->support.pairs.size()) < settings.false_match_probability)) return std::nullopt;
  // Another passing hypothesis that pairs a landmark of the best's support differently: two
  // places fit, neither is known.
  std::unordered_map<int, int> old_of_recent, recent_of_old;
  for (const auto& [o, r] : best->support.pairs) old_of_recent[r] = o, recent_of_old[o] = r;
  for (const Hypothesis& h : kept) {
    if (!(chance(h.support.pairs.size()) < settings.false_match_probability)) continue;
    for (const auto& [o, r] : h.support.pairs) {
      const auto by_recent = old_of_recent.find(r);
      const auto by_old = recent_of_old.find(o);
      if ((by_recent != old_of_recent.end() && by_recent->second != o) || (by_old != recent_of_old.end() && by_old->second != r))
        return std::nullopt;
    }
  }
  ConstellationMatch match{best->T, best->support.pairs, chance(best->support.pairs.size()), total};
  std::sort(match.pairs.begin(), match.pairs.end(), [](const auto& u, const auto& v) { return u.second < v.second; });
  return match;
}

}  // namespace slambox
