#include "eval/landmark_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "eval/assignment.hpp"
#include "eval/consistency.hpp"

namespace slambox {

namespace {
// Cost matrix min(c, d)^p between rows X and columns Y.
Eigen::MatrixXd CutoffCost(const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& Y, double c,
                           double p) {
  Eigen::MatrixXd cost(X.size(), Y.size());
  for (size_t i = 0; i < X.size(); ++i)
    for (size_t j = 0; j < Y.size(); ++j) cost(i, j) = std::pow(std::min(c, (X[i] - Y[j]).norm()), p);
  return cost;
}
}  // namespace

double OspaDistance(const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& Y, double c,
                    double p) {
  if (X.empty() && Y.empty()) return 0.0;
  if (X.empty() || Y.empty()) return c;
  const bool x_smaller = X.size() <= Y.size();
  const auto& small = x_smaller ? X : Y;
  const auto& large = x_smaller ? Y : X;
  const Eigen::MatrixXd cost = CutoffCost(small, large, c, p);
  const std::vector<int> assignment = SolveAssignment(cost);
  double sum = 0.0;
  for (size_t i = 0; i < small.size(); ++i) sum += cost(i, assignment[i]);
  const double n = static_cast<double>(large.size());
  sum += std::pow(c, p) * (n - static_cast<double>(small.size()));
  return std::pow(sum / n, 1.0 / p);
}

LandmarkMapResult EvaluateLandmarkMap(const std::vector<LandmarkEstimate>& est, const std::vector<TrueLandmark>& truth,
                                      const SE2& T_gt_est, const LandmarkMapOptions& o) {
  LandmarkMapResult r;
  std::vector<Eigen::Vector2d> aligned, true_pos;
  for (const auto& l : est) aligned.push_back(T_gt_est * l.position);
  for (const auto& l : truth) true_pos.push_back(l.position);
  std::map<int, int> true_index_of_id;
  for (size_t k = 0; k < truth.size(); ++k) true_index_of_id[truth[k].id] = static_cast<int>(k);

  bool by_id = o.matching == LandmarkMatching::kById;
  if (o.matching == LandmarkMatching::kAuto) {
    by_id = !est.empty();
    for (const auto& l : est) by_id = by_id && true_index_of_id.count(l.id) > 0;
  }
  r.by_id = by_id;
  auto add_match = [&](int ei, int ti) {
    LandmarkMatch m{ei, ti, (aligned[ei] - true_pos[ti]).norm(), std::numeric_limits<double>::quiet_NaN()};
    if (est[ei].has_covariance) m.nees = LandmarkNees(truth[ti].position, est[ei].position, est[ei].covariance);
    r.matches.push_back(m);
  };
  if (by_id) {
    std::vector<char> true_used(truth.size(), 0);
    for (size_t e = 0; e < est.size(); ++e) {
      const auto it = true_index_of_id.find(est[e].id);
      if (it == true_index_of_id.end() || true_used[it->second]) continue;  // unknown or duplicate id
      true_used[it->second] = 1;
      add_match(static_cast<int>(e), it->second);
    }
  } else if (!est.empty() && !truth.empty()) {
    const Eigen::MatrixXd cost = CutoffCost(aligned, true_pos, o.ospa_cutoff_m, o.ospa_order);
    const std::vector<int> assignment = SolveAssignment(cost);
    for (size_t e = 0; e < est.size(); ++e)
      if (assignment[e] >= 0 && (aligned[e] - true_pos[assignment[e]]).norm() < o.ospa_cutoff_m)
        add_match(static_cast<int>(e), assignment[e]);
  }
  r.spurious = static_cast<int>(est.size() - r.matches.size());
  r.missed = static_cast<int>(truth.size() - r.matches.size());
  double sse = 0.0, nees_sum = 0.0;
  int nees_count = 0;
  for (const auto& m : r.matches) {
    sse += m.error_m * m.error_m;
    if (std::isfinite(m.nees)) {
      nees_sum += m.nees;
      ++nees_count;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.rmse_m = r.matches.empty() ? nan : std::sqrt(sse / static_cast<double>(r.matches.size()));
  r.anees = nees_count == 0 ? nan : nees_sum / nees_count;
  r.ospa_m = OspaDistance(aligned, true_pos, o.ospa_cutoff_m, o.ospa_order);
  return r;
}

}  // namespace slambox
