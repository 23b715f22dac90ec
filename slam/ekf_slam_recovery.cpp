// `EkfSlam`'s recovery of a scan that contradicts the predicted heading (unknown ids).
//
// The odometry model's covariance is evaluated at the *measured* increment. In a fast turn
// an odometry that under-reports a few steps (the true rotation is 1.8 deg per step, the
// measured one 0.0-0.3 deg) therefore also under-reports its own variance, exactly when its
// error is largest: the predicted heading is then 5 sigma off, every detection falls outside
// its gate, and the detections start landmarks at rotated positions that the next scans pair
// with — the map is built a second time, rotated (random park lm3_3, slam/README_landmark_slam.md).
//
// The test: with P_D(r_j) the detection probability at landmark j's predicted range, the map
// expects lambda = sum over confirmed landmarks in view of P_D(r_j) detections. A scan that
// pairs none has probability exp(-lambda) under the prediction; below the gate's own miss
// probability 1 - P_G it contradicts the prediction (the same level as every other test of the
// module). Its association is then searched again under a heading prior widened by 2, 4, 8,
// 16 times its standard deviation (process noise the odometry did not report); the first
// that pairs detections with two or more confirmed landmarks is kept, and with it the wider
// heading variance (the update then shrinks it by what the scan shows). If none does, the
// scan's association stands as it was.
#include <algorithm>
#include <cmath>

#include "slam/ekf_slam.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

double EkfSlam::ExpectedConfirmedDetections() const {
  const SE2 pose = state_.Pose();
  double lambda = 0.0;
  for (size_t j = 0; j < tracks_.size(); ++j) {
    if (!tracks_[j].confirmed) continue;
    const Eigen::Vector2d zp = PredictObservation(pose, state_.Landmark(static_cast<int>(j))).z;
    if (ExpectedInView(zp)) lambda += config_.estimate_detection_rate ? DetectionProbability(detection_, zp.x()) : 1.0;
  }
  return lambda;
}

int EkfSlam::PairedConfirmedLandmarks(const std::vector<int>& target) const {
  // JCBB pairs each landmark at most once.
  return static_cast<int>(std::count_if(target.begin(), target.end(), [&](int j) { return j >= 0 && tracks_[j].confirmed; }));
}

std::vector<int> EkfSlam::RecoverHeading(const std::vector<Eigen::Vector2d>& z, const AssociationGates& gates,
                                         std::vector<int> target, double t_s) {
  if (PairedConfirmedLandmarks(target) > 0) return target;
  if (!(std::exp(-ExpectedConfirmedDetections()) < 1.0 - gate_probability_)) return target;
  const double variance = state_.covariance(2, 2);
  for (const double widen : {2.0, 4.0, 8.0, 16.0}) {
    EkfSlamState trial = state_;
    trial.covariance(2, 2) += (widen * widen - 1.0) * variance;
    std::vector<int> widened = AssociateJcbb(trial, z, R_, gates).landmark;
    if (PairedConfirmedLandmarks(widened) >= 2) {
      state_.covariance(2, 2) = trial.covariance(2, 2);
      Record(t_s, "heading_widened", widen);
      return widened;
    }
  }
  Record(t_s, "heading_widened", 0.0);
  return target;
}

}  // namespace slambox
