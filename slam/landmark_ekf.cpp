#include "slam/landmark_ekf.hpp"

#include <Eigen/LU>
#include <cmath>

#include "slam/range_bearing.hpp"

namespace slambox {

double GaussianLogLikelihood(const Eigen::Vector2d& innovation, const Eigen::Matrix2d& S) {
  const double det = S.determinant();
  const double mahalanobis2 = innovation.dot(S.inverse() * innovation);
  return -std::log(2.0 * M_PI) - 0.5 * std::log(det) - 0.5 * mahalanobis2;
}

LandmarkMeasurement MeasureLandmark(const SE2& pose, const LandmarkGaussian& landmark, const Eigen::Vector2d& z,
                                    const Eigen::Matrix2d& R) {
  const ObservationPrediction p = PredictObservation(pose, landmark.mean);
  LandmarkMeasurement m;
  m.innovation = Innovation(z, p.z);
  m.H = p.J_z_landmark;
  m.Q = m.H * landmark.covariance * m.H.transpose() + R;
  m.log_likelihood = GaussianLogLikelihood(m.innovation, m.Q);
  return m;
}

LandmarkGaussian UpdateLandmark(const LandmarkGaussian& landmark, const LandmarkMeasurement& m) {
  const Eigen::Matrix2d K = landmark.covariance * m.H.transpose() * m.Q.inverse();
  LandmarkGaussian out = landmark;
  out.mean += K * m.innovation;
  const Eigen::Matrix2d P = (Eigen::Matrix2d::Identity() - K * m.H) * landmark.covariance;
  out.covariance = 0.5 * (P + P.transpose());
  return out;
}

LandmarkGaussian InitializeLandmark(const SE2& pose, const Eigen::Vector2d& z, const Eigen::Matrix2d& R) {
  const LandmarkInitialization init = InverseObservation(pose, z);
  LandmarkGaussian lm;
  lm.mean = init.landmark;
  lm.covariance = init.J_landmark_z * R * init.J_landmark_z.transpose();
  lm.counter = 1;
  return lm;
}

namespace {
struct ProposalTerms {
  Eigen::Vector2d innovation;
  Eigen::Matrix<double, 2, 3> H_x;
  Eigen::Matrix2d L;
};
ProposalTerms Terms(const PoseProposal& proposal, const LandmarkGaussian& landmark, const Eigen::Vector2d& z,
                    const Eigen::Matrix2d& R) {
  const ObservationPrediction p = PredictObservation(proposal.mean, landmark.mean);
  ProposalTerms t;
  t.innovation = Innovation(z, p.z);
  t.H_x = p.J_z_pose;
  t.L = t.H_x * proposal.covariance * t.H_x.transpose() +
        p.J_z_landmark * landmark.covariance * p.J_z_landmark.transpose() + R;
  return t;
}
}  // namespace

double ProposalLogLikelihood(const PoseProposal& proposal, const LandmarkGaussian& landmark,
                             const Eigen::Vector2d& z, const Eigen::Matrix2d& R) {
  const ProposalTerms t = Terms(proposal, landmark, z, R);
  return GaussianLogLikelihood(t.innovation, t.L);
}

PredictedMeasurement PredictMeasurement(const PoseProposal& prior, const LandmarkGaussian& landmark,
                                        const Eigen::Matrix2d& R) {
  const ObservationPrediction p = PredictObservation(prior.mean, landmark.mean);
  const Eigen::Matrix2d L = p.J_z_pose * prior.covariance * p.J_z_pose.transpose() +
                            p.J_z_landmark * landmark.covariance * p.J_z_landmark.transpose() + R;
  return {p.z, L.inverse(), -std::log(2.0 * M_PI) - 0.5 * std::log(L.determinant())};
}

double ConditionProposal(PoseProposal& proposal, const LandmarkGaussian& landmark, const Eigen::Vector2d& z,
                         const Eigen::Matrix2d& R) {
  const ProposalTerms t = Terms(proposal, landmark, z, R);
  const Eigen::Matrix<double, 3, 2> K = proposal.covariance * t.H_x.transpose() * t.L.inverse();
  proposal.mean = SE2::FromVector(proposal.mean.vector() + K * t.innovation);
  const Eigen::Matrix3d P = (Eigen::Matrix3d::Identity() - K * t.H_x) * proposal.covariance;
  proposal.covariance = 0.5 * (P + P.transpose());
  return GaussianLogLikelihood(t.innovation, t.L);
}

}  // namespace slambox
