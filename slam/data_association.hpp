#pragma once
// Data association for EKF-SLAM with unknown landmark ids. Individual compatibility is
// the Mahalanobis distance d^2 = ν^T S^-1 ν of an observation against a mapped landmark
// (S from the robot, landmark and cross covariance blocks only: O(1) per pair).
//  - Nearest neighbour with two gates (Bailey's ekfslam data_associate): the closest
//    landmark is accepted if d^2 < gate_accept; if every d^2 > gate_new the observation
//    is a new landmark; in between it is ambiguous and discarded.
//  - JCBB (Neira & Tardós 2001): branch and bound over individually compatible pairings
//    for the largest jointly compatible hypothesis (joint d^2 below the chi-square
//    quantile with 2k dof), ties broken by the smaller joint d^2.
#include <Eigen/Core>
#include <vector>

#include "slam/ekf_slam_filter.hpp"
#include "slam/landmark_existence.hpp"  // ExpectedInGate, ExpectedFalseInGate

namespace slambox {

struct AssociationGates {
  double accept_chi2 = 9.21;   ///< [chi2, 2 dof] match if the nearest d^2 is below (99%)
  double new_chi2 = 25.0;      ///< [chi2, 2 dof] new landmark if every d^2 is above
  double joint_probability = 0.99;  ///< JCBB joint compatibility confidence
  int jcbb_max_nodes = 20000;  ///< JCBB search budget (nodes); the best found so far is kept
};

/// Per observation: the landmark it is matched to, or kNew / kDiscard.
struct Association {
  static constexpr int kNew = -1;
  static constexpr int kDiscard = -2;
  std::vector<int> landmark;           ///< per observation
  std::vector<double> nearest_chi2;    ///< per observation, d^2 to the nearest landmark (inf if none)
  int jcbb_nodes = 0;                  ///< nodes expanded (JCBB only)
};

/// Innovation covariance S = H P H^T + R of observing landmark `index` of `state`.
Eigen::Matrix2d InnovationCovariance(const EkfSlamState& state, int index, const Eigen::Matrix2d& R);

/// d^2 of observation z against landmark `index` of `state`.
double MahalanobisSquared(const EkfSlamState& state, int index, const Eigen::Vector2d& z, const Eigen::Matrix2d& R);

/// Nearest neighbour with two gates; each landmark takes at most one observation (the
/// closest; a loser is discarded).
Association AssociateNearestNeighbour(const EkfSlamState& state, const std::vector<Eigen::Vector2d>& z,
                                      const Eigen::Matrix2d& R, const AssociationGates& gates);

/// JCBB; unpaired observations become new landmarks or are discarded by the two gates.
Association AssociateJcbb(const EkfSlamState& state, const std::vector<Eigen::Vector2d>& z,
                          const Eigen::Matrix2d& R, const AssociationGates& gates);

/// Joint innovation covariance (2k x 2k) of a hypothesis (pairs of observation index,
/// landmark index), correlated through the robot pose; and the joint innovation.
struct JointInnovation {
  Eigen::VectorXd nu;
  Eigen::MatrixXd S;
};
JointInnovation JointInnovationOf(const EkfSlamState& state, const std::vector<Eigen::Vector2d>& z,
                                  const Eigen::Matrix2d& R, const std::vector<std::pair<int, int>>& pairs);

/// Per pair of a hypothesis, the innovation covariance of that pair conditioned on the
/// other pairs (the Schur complement S_qq - S_q,rest S_rest^-1 S_rest,q of the joint S):
/// how well the hypothesis pins the pair down beyond what the others already say.
std::vector<Eigen::Matrix2d> ConditionalInnovationCovariances(const Eigen::MatrixXd& S_joint);

/// Joint d^2 of a hypothesis (pairs of observation index, landmark index) with its
/// correlations through the robot pose.
double JointMahalanobisSquared(const EkfSlamState& state, const std::vector<Eigen::Vector2d>& z,
                               const Eigen::Matrix2d& R, const std::vector<std::pair<int, int>>& pairs);


}  // namespace slambox
