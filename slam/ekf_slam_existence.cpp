// The existence side of `ekf-slam` with unknown ids: the clutter expected in each gate,
// the prior odds of a new landmark, Wald's sequential test and the existence counts per
// scan (slam/landmark_existence.hpp, slam/detection_rate.hpp; slam/ekf_slam.hpp).
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "slam/ekf_slam.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

std::vector<double> EkfSlam::ExpectedClutterInGates() const {
  std::vector<double> mu(tracks_.size(), 0.0);
  if (known_ids_ || !(clutter_density_per_m2_ > 0)) return mu;
  const SE2 pose = state_.Pose();
  for (size_t j = 0; j < tracks_.size(); ++j) {
    const int index = static_cast<int>(j);
    const double range_m = PredictObservation(pose, state_.Landmark(index)).z.x();
    mu[j] = ExpectedFalseInGate(InnovationCovariance(state_, index, R_), range_m, config_.gate_accept_chi2,
                                clutter_density_per_m2_);
  }
  return mu;
}

double EkfSlam::NewLandmarkPriorLogRatio() const {
  return slambox::NewLandmarkPriorLogRatio(births_, scan_ + 1.0, clutter_per_scan_);
}

double EkfSlam::NewLandmarkDensity() const {
  // The first scan that maps anything maps its whole footprint at once: its births are no
  // sample of the rate at which unmapped landmarks come into view (held-out park lm9_2, 34
  // posts in the first scan: the rate read 17 per scan, every gate looked uncertain, and
  // the closure test forked on every scan). The rate is counted over the scans after it.
  if (first_birth_scan_ < 0 || scan_ <= first_birth_scan_) return 0.0;
  return UnmappedLandmarkDensity(births_ - first_scan_births_, scan_ - first_birth_scan_, clutter_per_scan_,
                                 range_max_m_ * range_max_m_ * half_fov_rad_, 0.0);
}

bool EkfSlam::ReadyToConfirm(const LandmarkTrack& t) const {
  return config_.tentative_existence == ExistenceRule::kSequentialTest ? t.log_ratio >= wald_.log_confirm
                                                                      : t.sightings >= config_.confirm_sightings;
}

void EkfSlam::UpdateTrack(LandmarkTrack& t, bool paired, bool held, double p_detect_in_view) const {
  if (paired) {
    if (!t.tracked) t.track_log_fake = 0.0;  // placed: a new track starts
    t.tracked = true;
    t.pose_covariance_when_placed = state_.covariance.topLeftCorner<3, 3>();
  }
  if (paired || (held && t.tracked)) {
    t.log_missed_since_seen = 0.0;
    return;
  }
  // Held after its track ended, or out of view (the robot may drift away unseen): ended.
  if (held || p_detect_in_view < 0.0) {
    t.tracked = false;
    return;
  }
  const double p_detect = config_.estimate_detection_rate ? p_detect_in_view : 1.0;
  t.log_missed_since_seen += std::log1p(-std::min(p_detect, 1.0));
  if (t.log_missed_since_seen <= std::log(1.0 - gate_probability_)) t.tracked = false;
}

bool EkfSlam::DriftedSincePlaced(int j) const {
  // The drift since the landmark was placed, seen in its predicted detection: J dP J^T,
  // against one detection's gate: drifted once in some direction it leaves the gate
  // d^2 < gate_accept_chi2 of noise R, i.e. the largest eigenvalue of L^-1 J dP J^T L^-T
  // (R = L L^T) is above gate_accept_chi2. Until then the object that made the landmark
  // is still inside the gate its repeats are paired in.
  const Eigen::Matrix3d dP = state_.covariance.topLeftCorner<3, 3>() - tracks_[j].pose_covariance_when_placed;
  const Eigen::Matrix<double, 2, 3> J = PredictObservation(state_.Pose(), state_.Landmark(j)).J_z_pose;
  const Eigen::LLT<Eigen::Matrix2d> llt(R_);
  const Eigen::Matrix2d half = llt.matrixL().solve(J * dP * J.transpose());
  const Eigen::Matrix2d whitened = llt.matrixL().solve(half.transpose());
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(whitened, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff() >
         config_.gate_accept_chi2;
}

void EkfSlam::ManageExistence(const std::vector<bool>& matched, const std::vector<bool>& held,
                              const std::vector<double>& mu, double t_s) {
  if (known_ids_) return;  // a known id names a real landmark: never removed
  const SE2 pose = state_.Pose();
  for (int j = static_cast<int>(matched.size()) - 1; j >= 0; --j) {
    LandmarkTrack& t = tracks_[j];
    const bool was_confirmed = t.confirmed;
    const bool seen = matched[j] || held[j];  // held: seen, not missed
    const bool tentative_sprt = config_.tentative_existence == ExistenceRule::kSequentialTest;
    if (!tentative_sprt && seen) t.confirmed = t.confirmed || ReadyToConfirm(t);
    const Eigen::Vector2d zp = PredictObservation(pose, state_.Landmark(j)).z;
    const bool in_view = ExpectedInView(zp);
    UpdateTrack(t, matched[j], held[j], in_view ? DetectionProbability(detection_, zp.x()) : -1.0);
    // Not confirmed in time: with counts at any place, with the sequential test only out
    // of view, where no trial can decide it (nor should it stay where a later real
    // observation could be paired with it).
    if (!t.confirmed && (!tentative_sprt || !in_view) && t_s - t.created_t_s > config_.tentative_max_age_s) {
      RemoveLandmark(state_, j);
      tracks_.erase(tracks_.begin() + j);
      continue;
    }
    if (!in_view) {
      // A miss is evidence only where a detection was expected; a detection is evidence
      // anywhere (a landmark seen only near range_max would otherwise never be tried).
      if (matched[j] && !held[j]) {
        const double p_band = config_.estimate_detection_rate ? DetectionProbability(detection_, zp.x()) : 1.0;
        t.log_ratio += DetectedLogRatio(p_band, gate_probability_, mu[j]);
        if (tentative_sprt) t.confirmed = t.confirmed || ReadyToConfirm(t);
      }
      continue;
    }
    // Counts: a miss costs how likely a detection was (before this scan): P_D at this
    // range over the confirmed landmarks, for a confirmed one times its own visibility,
    // its detections over those P_D predicted for it (a tentative one's history is too short).
    const double band = DetectionProbability(detection_, zp.x());
    const double visibility = t.confirmed ? (t.detected_scans + 1.0) / (t.expected_detections + 1.0) : 1.0;
    const double cost = config_.estimate_detection_rate ? std::min(1.0, band * visibility) : 1.0;
    // Confirmed landmarks (before this scan: its own sighting may have confirmed it) measure P_D.
    if (was_confirmed) CountExpected(detection_, zp.x(), seen);
    t.expected_detections += band;
    if (seen) t.detected_scans += 1.0;
    // A trial of the sequential test takes P_D at this range, not the landmark's own
    // visibility: that is estimated from the very trials under test, and a phantom's few
    // sightings would make its misses ever cheaper. A held pairing is no evidence either way.
    const double p_detect = config_.estimate_detection_rate ? band : 1.0;
    if (!held[j])
      t.log_ratio += matched[j] ? DetectedLogRatio(p_detect, gate_probability_, mu[j])
                                : MissedLogRatio(p_detect, gate_probability_, mu[j]);
    if (!seen) {
      t.misses += cost;
      t.existence -= cost;
    }
    if (tentative_sprt && matched[j]) t.confirmed = t.confirmed || ReadyToConfirm(t);  // by a sighting
    const ExistenceRule rule = t.confirmed ? config_.confirmed_existence : config_.tentative_existence;
    const bool remove = rule == ExistenceRule::kSequentialTest ? t.log_ratio <= wald_.log_delete
                        : t.confirmed                          ? !seen && t.existence <= 0
                                                               : !seen && t.misses >= config_.tentative_max_misses;
    if (remove) {
      RemoveLandmark(state_, j);
      tracks_.erase(tracks_.begin() + j);
    }
  }
}

}  // namespace slambox
