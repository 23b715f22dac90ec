#include "eval/rpe.hpp"

#include <cassert>
#include <cmath>

#include "eval/association.hpp"

namespace slambox {

namespace {
std::vector<IndexPair> Consecutive(const std::vector<int>& ids) {
  std::vector<IndexPair> pairs;
  for (size_t k = 1; k < ids.size(); ++k) pairs.emplace_back(ids[k - 1], ids[k]);
  return pairs;
}

std::vector<IndexPair> PairsByFrames(int n, int delta, bool all_pairs) {
  std::vector<IndexPair> pairs;
  if (delta < 1) return pairs;
  if (all_pairs) {
    for (int i = 0; i + delta < n; ++i) pairs.emplace_back(i, i + delta);
    return pairs;
  }
  std::vector<int> ids;
  for (int i = 0; i < n; i += delta) ids.push_back(i);
  return Consecutive(ids);
}

std::vector<IndexPair> PairsByPath(const std::vector<SE2>& poses, double delta, double tol, bool all_pairs) {
  std::vector<IndexPair> pairs;
  const int n = static_cast<int>(poses.size());
  if (all_pairs) {
    const std::vector<double> d = CumulativeDistance(poses);
    for (int i = 0; i + 1 < n; ++i) {
      int best = i + 1;  // argmin over j > i of |(d_j - d_i) - delta|, first on ties
      double best_err = std::abs((d[i + 1] - d[i]) - delta);
      for (int j = i + 2; j < n; ++j) {
        const double err = std::abs((d[j] - d[i]) - delta);
        if (err < best_err) {
          best_err = err;
          best = j;
        } else if ((d[j] - d[i]) - delta > best_err) {
          break;  // d is non-decreasing: every later j is farther from delta
        }
      }
      if (best_err <= tol) pairs.emplace_back(i, best);
    }
    return pairs;
  }
  std::vector<int> ids;
  double path = 0.0;
  for (int i = 0; i < n; ++i) {
    if (i > 0) {
      const double dx = poses[i].x - poses[i - 1].x, dy = poses[i].y - poses[i - 1].y;
      path += std::sqrt(dx * dx + dy * dy);
    }
    if (path >= delta) {
      ids.push_back(i);
      path = 0.0;
    }
  }
  return Consecutive(ids);
}

std::vector<IndexPair> PairsByAngle(const std::vector<SE2>& poses, double delta_deg, double tol_deg, bool all_pairs) {
  std::vector<IndexPair> pairs;
  const int n = static_cast<int>(poses.size());
  const double delta = delta_deg * M_PI / 180.0, tol = tol_deg * M_PI / 180.0;
  if (all_pairs) {
    for (int i = 0; i + 1 < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        const double a = std::abs(NormalizeAngle(poses[j].theta - poses[i].theta));
        if (delta - tol <= a && a <= delta + tol) pairs.emplace_back(i, j);
      }
    return pairs;
  }
  double accumulated = 0.0;
  int start = 0;
  for (int i = 0; i + 1 < n; ++i) {
    accumulated += std::abs(NormalizeAngle(poses[i + 1].theta - poses[i].theta));
    if (accumulated >= delta) {
      pairs.emplace_back(start, i + 1);
      accumulated = 0.0;
      start = i + 1;
    }
  }
  return pairs;
}
}  // namespace

std::vector<IndexPair> SelectPairs(const std::vector<SE2>& poses, const RpeOptions& o) {
  switch (o.unit) {
    case DeltaUnit::kFrames:
      return PairsByFrames(static_cast<int>(poses.size()), static_cast<int>(std::lround(o.delta)), o.all_pairs);
    case DeltaUnit::kMeters:
      return PairsByPath(poses, o.delta, o.delta * o.rel_delta_tol, o.all_pairs);
    case DeltaUnit::kDegrees:
      return PairsByAngle(poses, o.delta, o.delta * o.rel_delta_tol, o.all_pairs);
  }
  return {};
}

SE2 RelativePoseError(const SE2& Q_i, const SE2& Q_j, const SE2& P_i, const SE2& P_j) {
  const SE2 Q_rel = Between(Q_i, Q_j), P_rel = Between(P_i, P_j);
  // Q_rel^-1 P_rel = (R_q^T (t_p - t_q), theta_p - theta_q).
  const Eigen::Vector2d t = Q_rel.rotation().transpose() * (P_rel.translation() - Q_rel.translation());
  SE2 E;
  E.x = t.x();
  E.y = t.y();
  E.theta = NormalizeAngle(P_rel.theta - Q_rel.theta);
  return E;
}

RpeResult ComputeRpe(const std::vector<SE2>& gt, const std::vector<SE2>& est, const RpeOptions& o) {
  assert(gt.size() == est.size());
  RpeResult r;
  r.pairs = SelectPairs(o.pairs_from_reference ? gt : est, o);
  for (const auto& [i, j] : r.pairs) {
    const SE2 E = RelativePoseError(gt[i], gt[j], est[i], est[j]);
    r.translation_m.push_back(std::sqrt(E.x * E.x + E.y * E.y));
    r.rotation_deg.push_back(std::abs(E.theta) * 180.0 / M_PI);
  }
  return r;
}

bool ParseDeltaUnit(const std::string& text, DeltaUnit& unit) {
  if (text == "m" || text == "meters" || text == "metres") unit = DeltaUnit::kMeters;
  else if (text == "f" || text == "frames") unit = DeltaUnit::kFrames;
  else if (text == "d" || text == "deg" || text == "degrees") unit = DeltaUnit::kDegrees;
  else return false;
  return true;
}

std::string DeltaUnitName(DeltaUnit unit) {
  switch (unit) {
    case DeltaUnit::kFrames: return "f";
    case DeltaUnit::kMeters: return "m";
    case DeltaUnit::kDegrees: return "d";
  }
  return "?";
}

}  // namespace slambox
