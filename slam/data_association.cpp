#include "slam/data_association.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/chi_square.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

Eigen::Matrix2d InnovationCovariance(const EkfSlamState& s, int index, const Eigen::Matrix2d& R) {
  const ObservationPrediction p = PredictObservation(s.Pose(), s.Landmark(index));
  const int a = 3 + 2 * index;
  const Eigen::Matrix3d P_rr = s.covariance.topLeftCorner<3, 3>();
  const Eigen::Matrix<double, 3, 2> P_rm = s.covariance.block<3, 2>(0, a);
  const Eigen::Matrix2d P_mm = s.covariance.block<2, 2>(a, a);
  const Eigen::Matrix2d cross = p.J_z_pose * P_rm * p.J_z_landmark.transpose();
  return p.J_z_pose * P_rr * p.J_z_pose.transpose() + cross + cross.transpose() +
         p.J_z_landmark * P_mm * p.J_z_landmark.transpose() + R;
}

double ExpectedInGate(const Eigen::Matrix2d& C, double gate_chi2, double density_per_m2) {
  return density_per_m2 * M_PI * gate_chi2 * std::sqrt(std::max(0.0, C.determinant()));
}

double ExpectedFalseInGate(const Eigen::Matrix2d& S, double range_m, double gate_chi2, double density_per_m2) {
  return ExpectedInGate(S, gate_chi2, density_per_m2) * range_m;
}

double MahalanobisSquared(const EkfSlamState& s, int index, const Eigen::Vector2d& z, const Eigen::Matrix2d& R) {
  const Eigen::Vector2d nu = Innovation(z, PredictObservation(s.Pose(), s.Landmark(index)).z);
  return nu.dot(InnovationCovariance(s, index, R).ldlt().solve(nu));
}

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

/// d2[i][j] for every observation i and landmark j.
std::vector<std::vector<double>> CompatibilityTable(const EkfSlamState& s, const std::vector<Eigen::Vector2d>& z,
                                                    const Eigen::Matrix2d& R) {
  std::vector<std::vector<double>> d2(z.size(), std::vector<double>(s.NumLandmarks(), kInf));
  for (size_t i = 0; i < z.size(); ++i)
    for (int j = 0; j < s.NumLandmarks(); ++j) d2[i][j] = MahalanobisSquared(s, j, z[i], R);
  return d2;
}

void ApplyTwoGates(const std::vector<std::vector<double>>& d2, const AssociationGates& g, Association& a) {
  for (size_t i = 0; i < d2.size(); ++i) {
    a.nearest_chi2[i] = d2[i].empty() ? kInf : *std::min_element(d2[i].begin(), d2[i].end());
    if (a.landmark[i] < 0) a.landmark[i] = a.nearest_chi2[i] > g.new_chi2 ? Association::kNew : Association::kDiscard;
  }
}
}  // namespace

Association AssociateNearestNeighbour(const EkfSlamState& s, const std::vector<Eigen::Vector2d>& z,
                                      const Eigen::Matrix2d& R, const AssociationGates& gates) {
  const auto d2 = CompatibilityTable(s, z, R);
  Association a{std::vector<int>(z.size(), Association::kDiscard), std::vector<double>(z.size(), kInf), 0};
  std::vector<int> owner(s.NumLandmarks(), -1);
  for (size_t i = 0; i < z.size(); ++i) {
    const auto best = std::min_element(d2[i].begin(), d2[i].end());
    if (best == d2[i].end() || *best >= gates.accept_chi2) continue;
    const int j = static_cast<int>(best - d2[i].begin());
    if (owner[j] >= 0 && d2[owner[j]][j] <= *best) continue;  // the closer observation keeps it
    if (owner[j] >= 0) a.landmark[owner[j]] = Association::kDiscard;
    owner[j] = static_cast<int>(i);
    a.landmark[i] = j;
  }
  ApplyTwoGates(d2, gates, a);  // a loser of a contested landmark has d^2 < accept: discarded
  return a;
}

JointInnovation JointInnovationOf(const EkfSlamState& s, const std::vector<Eigen::Vector2d>& z,
                                  const Eigen::Matrix2d& R, const std::vector<std::pair<int, int>>& pairs) {
  const int k = static_cast<int>(pairs.size());
  // H over the sub-state (robot, paired landmarks): 2k x (3 + 2k).
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * k, 3 + 2 * k), P(3 + 2 * k, 3 + 2 * k);
  JointInnovation out{Eigen::VectorXd(2 * k), Eigen::MatrixXd()};
  std::vector<int> rows = {0, 1, 2};
  for (int q = 0; q < k; ++q) {
    const auto [i, j] = pairs[q];
    const ObservationPrediction p = PredictObservation(s.Pose(), s.Landmark(j));
    H.block<2, 3>(2 * q, 0) = p.J_z_pose;
    H.block<2, 2>(2 * q, 3 + 2 * q) = p.J_z_landmark;
    out.nu.segment<2>(2 * q) = Innovation(z[i], p.z);
    rows.push_back(3 + 2 * j);
    rows.push_back(4 + 2 * j);
  }
  for (int r = 0; r < 3 + 2 * k; ++r)
    for (int c = 0; c < 3 + 2 * k; ++c) P(r, c) = s.covariance(rows[r], rows[c]);
  out.S = H * P * H.transpose();
  for (int q = 0; q < k; ++q) out.S.block<2, 2>(2 * q, 2 * q) += R;
  return out;
}

std::vector<Eigen::Matrix2d> ConditionalInnovationCovariances(const Eigen::MatrixXd& S) {
  const int k = static_cast<int>(S.rows()) / 2;
  std::vector<Eigen::Matrix2d> out(k);
  for (int q = 0; q < k; ++q) {
    // Reorder as (rest, q) and take the Schur complement of the rest.
    std::vector<int> rest;
    for (int r = 0; r < 2 * k; ++r)
      if (r / 2 != q) rest.push_back(r);
    const int n = static_cast<int>(rest.size());
    Eigen::MatrixXd S_rr(n, n), S_rq(n, 2);
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) S_rr(a, b) = S(rest[a], rest[b]);
      S_rq.row(a) = S.block<1, 2>(rest[a], 2 * q);
    }
    const Eigen::Matrix2d S_qq = S.block<2, 2>(2 * q, 2 * q);
    out[q] = n == 0 ? S_qq : Eigen::Matrix2d(S_qq - S_rq.transpose() * S_rr.ldlt().solve(S_rq));
  }
  return out;
}

double JointMahalanobisSquared(const EkfSlamState& s, const std::vector<Eigen::Vector2d>& z,
                               const Eigen::Matrix2d& R, const std::vector<std::pair<int, int>>& pairs) {
  const JointInnovation j = JointInnovationOf(s, z, R, pairs);
  return j.nu.dot(j.S.ldlt().solve(j.nu));
}

namespace {
struct JcbbSearch {
  const EkfSlamState& s;
  const std::vector<Eigen::Vector2d>& z;
  const Eigen::Matrix2d& R;
  const std::vector<std::vector<int>>& candidates;  // individually compatible landmarks per observation
  const AssociationGates& gates;
  std::vector<std::pair<int, int>> current, best;
  double best_d2 = kInf;
  std::vector<bool> used;
  int nodes = 0;

  void Recurse(size_t i) {
    if (++nodes > gates.jcbb_max_nodes) return;
    if (i == z.size()) {
      const double d2 = current.empty() ? 0.0 : JointMahalanobisSquared(s, z, R, current);
      if (current.size() > best.size() || (current.size() == best.size() && d2 < best_d2)) {
        best = current;
        best_d2 = d2;
      }
      return;
    }
    for (int j : candidates[i]) {
      if (used[j]) continue;
      current.emplace_back(static_cast<int>(i), j);
      const int dof = 2 * static_cast<int>(current.size());
      if (JointMahalanobisSquared(s, z, R, current) < ChiSquareQuantile(gates.joint_probability, dof)) {
        used[j] = true;
        Recurse(i + 1);
        used[j] = false;
      }
      current.pop_back();
    }
    // Leave observation i unpaired only if that can still beat the best (the bound).
    if (current.size() + (z.size() - i - 1) > best.size()) Recurse(i + 1);
  }
};
}  // namespace

Association AssociateJcbb(const EkfSlamState& s, const std::vector<Eigen::Vector2d>& z, const Eigen::Matrix2d& R,
                          const AssociationGates& gates) {
  const auto d2 = CompatibilityTable(s, z, R);
  std::vector<std::vector<int>> candidates(z.size());
  for (size_t i = 0; i < z.size(); ++i) {
    for (int j = 0; j < s.NumLandmarks(); ++j)
      if (d2[i][j] < gates.accept_chi2) candidates[i].push_back(j);
    std::sort(candidates[i].begin(), candidates[i].end(), [&](int a, int b) { return d2[i][a] < d2[i][b]; });
  }
  JcbbSearch search{s, z, R, candidates, gates, {}, {}, kInf, std::vector<bool>(s.NumLandmarks(), false)};
  search.Recurse(0);
  Association a{std::vector<int>(z.size(), Association::kDiscard), std::vector<double>(z.size(), kInf),
                search.nodes};
  for (const auto& [i, j] : search.best) a.landmark[i] = j;
  ApplyTwoGates(d2, gates, a);
  return a;
}

}  // namespace slambox
