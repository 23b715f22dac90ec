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

namespace {
/// One pairing's linearization: ν = z_i - h(x, m_j) ≈ J_pose δx + J_landmark δm_j.
struct PairLinearization {
  int landmark = 0;
  Eigen::Matrix<double, 2, 3> J_pose;
  Eigen::Matrix2d J_landmark;
  Eigen::Vector2d nu;
};

PairLinearization Linearize(const EkfSlamState& s, const std::vector<Eigen::Vector2d>& z, std::pair<int, int> pair) {
  const auto [i, j] = pair;
  const ObservationPrediction p = PredictObservation(s.Pose(), s.Landmark(j));
  return {j, p.J_z_pose, p.J_z_landmark, Innovation(z[i], p.z)};
}

/// Cov(ν_a, ν_b) = [Ja_x Ja_m] [P_xx P_x,mb; P_ma,x P_ma,mb] [Jb_x Jb_m]^T, without R: the
/// block (a, b) of H P H^T read from the four covariance blocks it needs, O(1) per pair of
/// pairings where the dense product is O(k) per block.
Eigen::Matrix2d CrossCovariance(const EkfSlamState& s, const PairLinearization& a, const PairLinearization& b) {
  const int ia = 3 + 2 * a.landmark, ib = 3 + 2 * b.landmark;
  const Eigen::Matrix<double, 2, 3> A = a.J_pose * s.covariance.topLeftCorner<3, 3>() +
                                        a.J_landmark * s.covariance.block<2, 3>(ia, 0);
  const Eigen::Matrix2d B = a.J_pose * s.covariance.block<3, 2>(0, ib) + a.J_landmark * s.covariance.block<2, 2>(ia, ib);
  return A * b.J_pose.transpose() + B * b.J_landmark.transpose();
}
}  // namespace

JointInnovation JointInnovationOf(const EkfSlamState& s, const std::vector<Eigen::Vector2d>& z,
                                  const Eigen::Matrix2d& R, const std::vector<std::pair<int, int>>& pairs) {
  const int k = static_cast<int>(pairs.size());
  std::vector<PairLinearization> lin;
  lin.reserve(k);
  for (const auto& pair : pairs) lin.push_back(Linearize(s, z, pair));
  JointInnovation out{Eigen::VectorXd(2 * k), Eigen::MatrixXd(2 * k, 2 * k)};
  for (int a = 0; a < k; ++a) {
    out.nu.segment<2>(2 * a) = lin[a].nu;
    for (int b = 0; b <= a; ++b) {
      Eigen::Matrix2d C = CrossCovariance(s, lin[a], lin[b]);
      if (a == b) C = 0.5 * (C + C.transpose()).eval();  // exactly symmetric
      out.S.block<2, 2>(2 * a, 2 * b) = C;
      out.S.block<2, 2>(2 * b, 2 * a) = C.transpose();
    }
    out.S.block<2, 2>(2 * a, 2 * a) += R;
  }
  return out;
}

std::vector<Eigen::Matrix2d> ConditionalInnovationCovariances(const Eigen::MatrixXd& S) {
  const int k = static_cast<int>(S.rows()) / 2;
  if (k == 1) return {Eigen::Matrix2d(S)};
  // S_qq - S_q,rest S_rest^-1 S_rest,q is the inverse of the (q, q) block of S^-1 (block
  // inversion): one factorization for all k pairs instead of one per pair.
  const Eigen::MatrixXd S_inv = S.ldlt().solve(Eigen::MatrixXd::Identity(2 * k, 2 * k));
  std::vector<Eigen::Matrix2d> out(k);
  for (int q = 0; q < k; ++q) {
    const Eigen::Matrix2d info = 0.5 * (S_inv.block<2, 2>(2 * q, 2 * q) + S_inv.block<2, 2>(2 * q, 2 * q).transpose());
    out[q] = info.inverse();
  }
  return out;
}

double JointMahalanobisSquared(const EkfSlamState& s, const std::vector<Eigen::Vector2d>& z,
                               const Eigen::Matrix2d& R, const std::vector<std::pair<int, int>>& pairs) {
  const JointInnovation j = JointInnovationOf(s, z, R, pairs);
  return j.nu.dot(j.S.ldlt().solve(j.nu));
}

namespace {
/// The joint d^2 of the hypothesis on the search's path, grown one pairing at a time: the
/// Cholesky factor L of the joint S of the first k pairings is the leading block of the
/// factor for k + 1, so adding pairing q costs one forward substitution (O(k^2)) instead of
/// a new factorization (O(k^3)). With S = L L^T and w = L^-1 ν, d^2 = |w|^2; the new rows
/// are Y^T = (L^-1 S_{1..k,q})^T, L_qq = chol(S_qq - Y^T Y), w_q = L_qq^-1 (ν_q - Y^T w).
class IncrementalJointD2 {
 public:
  IncrementalJointD2(const EkfSlamState& s, const Eigen::Matrix2d& R, int max_pairs)
      : s_(s), R_(R), L_(Eigen::MatrixXd::Zero(2 * max_pairs, 2 * max_pairs)), w_(2 * max_pairs),
        d2_(max_pairs + 1, 0.0) {
    path_.reserve(max_pairs);
  }

  /// Appends a pairing after the first `depth` (dropping deeper ones); returns the joint d^2
  /// of the `depth + 1` pairings (infinite if the joint S is not positive definite).
  double Push(int depth, const PairLinearization& q) {
    path_.resize(depth);
    const int n = 2 * depth;
    Eigen::MatrixXd B(n, 2);
    for (int p = 0; p < depth; ++p) B.middleRows<2>(2 * p) = CrossCovariance(s_, path_[p], q);
    const Eigen::MatrixXd Y = L_.topLeftCorner(n, n).triangularView<Eigen::Lower>().solve(B);
    const Eigen::Matrix2d M = CrossCovariance(s_, q, q) + R_ - Y.transpose() * Y;
    const double l11_sq = M(0, 0);
    if (!(l11_sq > 0.0)) return kInf;
    const double l11 = std::sqrt(l11_sq), l21 = M(1, 0) / l11, l22_sq = M(1, 1) - l21 * l21;
    if (!(l22_sq > 0.0)) return kInf;
    const double l22 = std::sqrt(l22_sq);
    L_.block(n, 0, 2, n) = Y.transpose();
    L_.block<2, 2>(n, n) << l11, 0.0, l21, l22;
    const Eigen::Vector2d r = q.nu - Y.transpose() * w_.head(n);
    const double w0 = r(0) / l11, w1 = (r(1) - l21 * w0) / l22;
    w_.segment<2>(n) << w0, w1;
    path_.push_back(q);
    d2_[depth + 1] = d2_[depth] + w0 * w0 + w1 * w1;
    return d2_[depth + 1];
  }

  double D2(int depth) const { return d2_[depth]; }

 private:
  const EkfSlamState& s_;
  const Eigen::Matrix2d& R_;
  Eigen::MatrixXd L_;
  Eigen::VectorXd w_;
  std::vector<double> d2_;
  std::vector<PairLinearization> path_;
};

struct JcbbSearch {
  const EkfSlamState& s;
  const std::vector<Eigen::Vector2d>& z;
  const std::vector<std::vector<int>>& candidates;  // individually compatible landmarks per observation
  const AssociationGates& gates;
  IncrementalJointD2 joint;
  std::vector<double> joint_gate;  // chi-square quantile per hypothesis size (2k dof), NaN until needed
  std::vector<std::pair<int, int>> current, best;
  double best_d2 = kInf;
  std::vector<bool> used;
  int nodes = 0;

  double JointGate(size_t k) {
    if (std::isnan(joint_gate[k])) joint_gate[k] = ChiSquareQuantile(gates.joint_probability, 2.0 * k);
    return joint_gate[k];
  }

  void Recurse(size_t i) {
    if (++nodes > gates.jcbb_max_nodes) return;
    if (i == z.size()) {
      const double d2 = joint.D2(static_cast<int>(current.size()));
      if (current.size() > best.size() || (current.size() == best.size() && d2 < best_d2)) {
        best = current;
        best_d2 = d2;
      }
      return;
    }
    for (int j : candidates[i]) {
      if (used[j]) continue;
      const std::pair<int, int> pair{static_cast<int>(i), j};
      const double d2 = joint.Push(static_cast<int>(current.size()), Linearize(s, z, pair));
      if (d2 < JointGate(current.size() + 1)) {
        current.push_back(pair);
        used[j] = true;
        Recurse(i + 1);
        used[j] = false;
        current.pop_back();
      }
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
  const int n = static_cast<int>(z.size());
  JcbbSearch search{s,  z,  candidates, gates, IncrementalJointD2(s, R, n), std::vector<double>(n + 1, std::nan("")),
                    {}, {}, kInf,       std::vector<bool>(s.NumLandmarks(), false)};
  search.Recurse(0);
  Association a{std::vector<int>(z.size(), Association::kDiscard), std::vector<double>(z.size(), kInf),
                search.nodes};
  for (const auto& [i, j] : search.best) a.landmark[i] = j;
  ApplyTwoGates(d2, gates, a);
  return a;
}

}  // namespace slambox
