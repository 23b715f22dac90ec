#include "slam/correlative_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace slambox {

namespace {
constexpr double kDegToRad = M_PI / 180.0;

struct Candidate {
  int rotation = 0;
  int x = 0, y = 0;  ///< offset from the guess [cells]
  double score = 0.0;
};

/// Source points rotated to one lattice heading, as cells at the zero offset.
struct RotatedScan {
  double theta_rad = 0.0;
  std::vector<Eigen::Vector2i> cells;
};

struct Lattice {
  std::vector<RotatedScan> scans;
  int window_cells = 0;
};

Lattice MakeLattice(const ScoreTable& table, const std::vector<Eigen::Vector2d>& source, const SE2& guess,
                    const CorrelativeSearchConfig& config) {
  if (!(config.linear_window_m >= 0) || !(config.angular_window_deg >= 0))
    throw std::invalid_argument("correlative search: windows must be >= 0");
  double step = config.angular_step_deg * kDegToRad;
  if (!(step > 0)) {
    double r = 0.0;
    for (const auto& p : source) r = std::max(r, p.norm());
    r = std::clamp(r, table.resolution_m, config.max_range_for_step_m);
    step = std::acos(1.0 - table.resolution_m * table.resolution_m / (2.0 * r * r));
  }
  const int n_theta = static_cast<int>(std::ceil(config.angular_window_deg * kDegToRad / step - 1e-9));
  Lattice l;
  l.window_cells = static_cast<int>(std::ceil(config.linear_window_m / table.resolution_m - 1e-9));
  for (int i = -n_theta; i <= n_theta; ++i) {
    RotatedScan s;
    s.theta_rad = guess.theta + i * step;
    const SE2 T(guess.x, guess.y, s.theta_rad);
    s.cells.reserve(source.size());
    for (const auto& p : source) s.cells.push_back(table.Cell(T * p));
    l.scans.push_back(std::move(s));
  }
  return l;
}

double Score(const ScoreTable& table, int level, const RotatedScan& s, int ox, int oy) {
  double sum = 0.0;
  for (const auto& c : s.cells) sum += table.At(level, c.x() + ox, c.y() + oy);
  return s.cells.empty() ? 0.0 : sum / static_cast<double>(s.cells.size());
}

CorrelativeMatch ToMatch(const ScoreTable& table, const Lattice& l, const SE2& guess, const Candidate& best,
                         bool found, int evaluated) {
  CorrelativeMatch m;
  m.found = found;
  m.evaluated = evaluated;
  if (!found) return m;
  m.score = best.score;
  const int n_theta = static_cast<int>(l.scans.size() / 2);
  m.at_window_edge = std::abs(best.x) == l.window_cells || std::abs(best.y) == l.window_cells ||
                     (n_theta > 0 && std::abs(best.rotation - n_theta) == n_theta);
  m.T_map_source = SE2(guess.x + best.x * table.resolution_m, guess.y + best.y * table.resolution_m,
                       NormalizeAngle(l.scans[static_cast<size_t>(best.rotation)].theta_rad));
  return m;
}

struct Search {
  const ScoreTable& table;
  const Lattice& lattice;
  double min_score;
  Candidate best;
  bool found = false;
  int evaluated = 0;
  bool exclude = false;           ///< leaves within exclude_cells2 of (exclude_x, exclude_y) are skipped
  int exclude_x = 0, exclude_y = 0;
  double exclude_cells2 = 0.0;
  std::vector<Candidate> roots_copy;

  // Depth-first over the children of candidates at `level`, best bound first.
  void Descend(std::vector<Candidate> candidates, int level) {
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
      return a.score > b.score;
    });
    for (const Candidate& c : candidates) {
      if (c.score < min_score || (found && c.score <= best.score)) break;  // sorted: the rest is worse
      if (level == 0) {
        const double dx = c.x - exclude_x, dy = c.y - exclude_y;
        if (exclude && dx * dx + dy * dy <= exclude_cells2) continue;
        best = c;
        found = true;
        continue;
      }
      const int half = 1 << (level - 1);
      std::vector<Candidate> children;
      for (int dx : {0, half})
        for (int dy : {0, half}) {
          const int x = c.x + dx, y = c.y + dy;
          if (x > lattice.window_cells || y > lattice.window_cells) continue;
          const auto& s = lattice.scans[static_cast<size_t>(c.rotation)];
          children.push_back({c.rotation, x, y, Score(table, level - 1, s, x, y)});
          ++evaluated;
        }
      Descend(std::move(children), level - 1);
    }
  }
};
}  // namespace

Eigen::Vector2i ScoreTable::Cell(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d f = (p - origin_m) / resolution_m;
  // Clamp before the int conversion so that far points stay defined (and outside).
  return {static_cast<int>(std::floor(std::clamp(f.x(), -1e8, 1e8))),
          static_cast<int>(std::floor(std::clamp(f.y(), -1e8, 1e8)))};
}

ScoreTable MakeScoreTable(const std::vector<Eigen::Vector2d>& map_points, const ScoreTableConfig& config,
                          const std::vector<Eigen::Vector2d>& viewpoints) {
  if (!(config.resolution_m > 0) || !(config.sigma_m > 0) || config.levels < 1 || config.levels > 12 ||
      !(config.unknown_score >= 0 && config.unknown_score <= 1))
    throw std::invalid_argument("score table: resolution_m and sigma_m must be > 0, levels in [1, 12], unknown_score in [0, 1]");
  const bool unknown = config.unknown_score > 0;
  if (unknown && viewpoints.size() != map_points.size())
    throw std::invalid_argument("score table: unknown_score > 0 needs one viewpoint per map point");
  ScoreTable t;
  t.resolution_m = config.resolution_m;
  t.outside = static_cast<float>(config.unknown_score);
  t.levels.assign(static_cast<size_t>(config.levels), {});
  if (map_points.empty()) return t;
  Eigen::Vector2d lo = map_points[0], hi = map_points[0];
  for (const auto& p : map_points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double reach_m = 3.0 * config.sigma_m;
  const double margin_m = reach_m + config.resolution_m * ((1 << (config.levels - 1)) + 1);
  t.origin_m = lo - Eigen::Vector2d::Constant(margin_m);
  t.width = static_cast<int>(std::ceil((hi.x() - lo.x() + 2 * margin_m) / config.resolution_m)) + 1;
  t.height = static_cast<int>(std::ceil((hi.y() - lo.y() + 2 * margin_m) / config.resolution_m)) + 1;
  const size_t cells = static_cast<size_t>(t.width) * static_cast<size_t>(t.height);
  std::vector<float> d2(cells, std::numeric_limits<float>::infinity());
  const int r = static_cast<int>(std::ceil(reach_m / config.resolution_m));
  for (const auto& p : map_points) {
    const Eigen::Vector2i c = t.Cell(p);
    for (int y = std::max(c.y() - r, 0); y <= std::min(c.y() + r, t.height - 1); ++y)
      for (int x = std::max(c.x() - r, 0); x <= std::min(c.x() + r, t.width - 1); ++x) {
        const Eigen::Vector2d centre = t.origin_m + (Eigen::Vector2d(x, y) + Eigen::Vector2d::Constant(0.5)) * t.resolution_m;
        float& v = d2[static_cast<size_t>(y) * static_cast<size_t>(t.width) + static_cast<size_t>(x)];
        v = std::min(v, static_cast<float>((centre - p).squaredNorm()));
      }
  }
  // Observed cells: those a ray from a viewpoint to its point crosses (sampled every half cell).
  std::vector<unsigned char> seen;
  if (unknown) {
    seen.assign(cells, 0);
    const double step_m = 0.5 * config.resolution_m;
    for (size_t i = 0; i < map_points.size(); ++i) {
      const Eigen::Vector2d a = viewpoints[i], ab = map_points[i] - a;
      const int n = static_cast<int>(std::ceil(std::min(ab.norm(), 1e4) / step_m));
      for (int k = 0; k <= n; ++k) {
        const Eigen::Vector2i c = t.Cell(a + ab * (n == 0 ? 1.0 : static_cast<double>(k) / n));
        if (c.x() >= 0 && c.y() >= 0 && c.x() < t.width && c.y() < t.height)
          seen[static_cast<size_t>(c.y()) * static_cast<size_t>(t.width) + static_cast<size_t>(c.x())] = 1;
      }
    }
  }
  // Level 0 in place of the squared distances; each pooled level written once, in order
  // (no zero fill first: the tables are large and this runs for every loop submap).
  const double reach2 = reach_m * reach_m, inv = 1.0 / (2.0 * config.sigma_m * config.sigma_m);
  for (size_t i = 0; i < cells; ++i) {
    float& v = d2[i];
    v = v <= reach2 ? static_cast<float>(std::exp(-v * inv)) : (unknown && !seen[i] ? t.outside : 0.0f);
  }
  t.levels[0] = std::move(d2);
  const size_t w = static_cast<size_t>(t.width);
  for (int h = 1; h < config.levels; ++h) {
    const size_t s = size_t{1} << (h - 1);
    const std::vector<float>& in = t.levels[static_cast<size_t>(h - 1)];
    std::vector<float> out;
    out.reserve(cells);
    for (size_t y = 0; y < static_cast<size_t>(t.height); ++y) {
      const float* row = in.data() + y * w;
      // Cells past the table's edge count as `outside`.
      const float* below = y + s < static_cast<size_t>(t.height) ? row + s * w : nullptr;
      for (size_t x = 0; x < w; ++x) {
        float v = row[x];
        if (x + s < w) v = std::max(v, row[x + s]);
        if (x + s >= w || !below) v = std::max(v, t.outside);
        if (below) {
          v = std::max(v, below[x]);
          if (x + s < w) v = std::max(v, below[x + s]);
        }
        out.push_back(v);
      }
    }
    t.levels[static_cast<size_t>(h)] = std::move(out);
  }
  return t;
}

double CorrelativeScore(const ScoreTable& table, const std::vector<Eigen::Vector2d>& source, const SE2& T) {
  double sum = 0.0;
  for (const auto& p : source) {
    const Eigen::Vector2i c = table.Cell(T * p);
    sum += table.At(0, c.x(), c.y());
  }
  return source.empty() ? 0.0 : sum / static_cast<double>(source.size());
}

CorrelativeMatch MatchCorrelative(const ScoreTable& table, const std::vector<Eigen::Vector2d>& source,
                                  const SE2& guess, const CorrelativeSearchConfig& config) {
  if (table.levels.empty() || table.width == 0 || source.empty()) return {};
  const Lattice l = MakeLattice(table, source, guess, config);
  const int top = static_cast<int>(table.levels.size()) - 1;
  const int step = 1 << top;
  Search search{table, l, config.min_score, {}, false, 0};
  std::vector<Candidate> roots;
  for (size_t i = 0; i < l.scans.size(); ++i)
    for (int x = -l.window_cells; x <= l.window_cells; x += step)
      for (int y = -l.window_cells; y <= l.window_cells; y += step) {
        roots.push_back({static_cast<int>(i), x, y, Score(table, top, l.scans[i], x, y)});
        ++search.evaluated;
      }
  Search runner_up = search;  // same roots, before the first pass consumes them
  runner_up.roots_copy = roots;
  runner_up.evaluated = 0;
  search.Descend(std::move(roots), top);
  CorrelativeMatch m = ToMatch(table, l, guess, search.best, search.found, search.evaluated);
  if (m.found && config.runner_up_radius_m > 0) {
    runner_up.exclude = true;
    runner_up.exclude_x = search.best.x;
    runner_up.exclude_y = search.best.y;
    const double r = config.runner_up_radius_m / table.resolution_m;
    runner_up.exclude_cells2 = r * r;
    runner_up.Descend(std::move(runner_up.roots_copy), top);
    m.evaluated += runner_up.evaluated;
    if (runner_up.found) m.runner_up_score = runner_up.best.score;
  }
  return m;
}

CorrelativeMatch MatchCorrelativeExhaustive(const ScoreTable& table, const std::vector<Eigen::Vector2d>& source,
                                            const SE2& guess, const CorrelativeSearchConfig& config) {
  if (table.levels.empty() || table.width == 0 || source.empty()) return {};
  const Lattice l = MakeLattice(table, source, guess, config);
  Candidate best;
  bool found = false;
  int evaluated = 0;
  for (size_t i = 0; i < l.scans.size(); ++i)
    for (int x = -l.window_cells; x <= l.window_cells; ++x)
      for (int y = -l.window_cells; y <= l.window_cells; ++y) {
        const double s = Score(table, 0, l.scans[i], x, y);
        ++evaluated;
        if (s >= config.min_score && (!found || s > best.score)) {
          best = {static_cast<int>(i), x, y, s};
          found = true;
        }
      }
  CorrelativeMatch m = ToMatch(table, l, guess, best, found, evaluated);
  if (!found || !(config.runner_up_radius_m > 0)) return m;
  const double r = config.runner_up_radius_m / table.resolution_m;
  for (size_t i = 0; i < l.scans.size(); ++i)
    for (int x = -l.window_cells; x <= l.window_cells; ++x)
      for (int y = -l.window_cells; y <= l.window_cells; ++y) {
        const double dx = x - best.x, dy = y - best.y;
        if (dx * dx + dy * dy <= r * r) continue;
        const double s = Score(table, 0, l.scans[i], x, y);
        if (s >= config.min_score) m.runner_up_score = std::max(m.runner_up_score, s);
      }
  return m;
}

}  // namespace slambox
