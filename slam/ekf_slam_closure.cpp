// The closure test of `ekf-slam` (issue 14, `forest`; slam/README_landmark_slam.md): a
// loop closure on uncertain evidence is decided by the scans that follow it, not by the
// scan that proposes it. See EkfSlam in slam/ekf_slam.hpp.
#include <cmath>

#include "slam/ekf_slam.hpp"
#include "slam/range_bearing.hpp"
#include "slam/scan_likelihood.hpp"

namespace slambox {

bool EkfSlam::MayStartClosureTest() const {
  return config_.closure_test && !known_ids_ && FakeDensity() > 0.0 && !blocks_closures_ &&
         closure_rival_.empty();
}

bool EkfSlam::UncertainGate(int landmark, double range_m) const {
  // The hold's criterion on the landmark's own gate, not the gate given the scan's other
  // pairings: two coincidences can pin each other down (forest seed 1).
  return ExpectedFalseInGate(InnovationCovariance(state_, landmark, R_), range_m, config_.gate_accept_chi2,
                             FakeDensity()) > 1.0 - gate_probability_;
}

bool EkfSlam::HasUncertainPairing(const std::vector<Eigen::Vector2d>& z, const std::vector<int>& target) const {
  for (size_t i = 0; i < z.size(); ++i)
    if (target[i] >= 0 && UncertainGate(target[i], z[i].x())) return true;
  return false;
}

void EkfSlam::BlockUncertainClosures(const std::vector<Eigen::Vector2d>& z, std::vector<int>& target) const {
  // Without the loop closure, a detection that only uncertain gates could explain (paired
  // or left ambiguous) is a landmark not mapped yet; one a certain gate holds stays as it is.
  for (size_t i = 0; i < z.size(); ++i) {
    if (target[i] == Association::kNew) continue;
    bool certain = target[i] >= 0 && !UncertainGate(target[i], z[i].x());
    for (int j = 0; j < state_.NumLandmarks() && target[i] < 0 && !certain; ++j)
      certain = MahalanobisSquared(state_, j, z[i], R_) < config_.gate_new_chi2 && !UncertainGate(j, z[i].x());
    if (!certain) target[i] = Association::kNew;
  }
}

void EkfSlam::StartClosureTest(const LandmarkEvent& event, const std::vector<Eigen::Vector2d>& z,
                               const std::vector<int>& target, const std::vector<bool>& held) {
  Record(event.t_s, "closure_tests", 1.0);
  fork_scan_ = scan_;  // this scan: the rival applies it without the closure
  test_fake_density_ = FakeDensity();
  EkfSlam rival = *this;
  rival.blocks_closures_ = true;
  std::vector<int> rival_target = target;
  rival.BlockUncertainClosures(z, rival_target);
  rival.ApplyScan(event, z, rival_target, held);
  closure_rival_.push_back(std::move(rival));
  closure_log_ratio_ = 0.0;  // this scan's likelihood is the same for both: computed before either update
}

void EkfSlam::StartClosureTestAtMerge(double t_s) {
  uncertain_merge_pending_ = false;
  Record(t_s, "closure_tests", 1.0);
  fork_scan_ = scan_;  // the next scan: this one's assignments were made before the merge
  test_fake_density_ = FakeDensity();
  EkfSlam rival = *this;
  rival.blocks_closures_ = true;
  closure_rival_.push_back(std::move(rival));
  closure_log_ratio_ = 0.0;
  const int merged = MergeDuplicates();
  // This scan's bookkeeping (ApplyScan) was written before the merge.
  int confirmed = 0;
  for (const auto& t : tracks_) confirmed += t.confirmed ? 1 : 0;
  estimate_.diagnostics["merged_landmarks"].back().second += merged;
  estimate_.diagnostics["num_landmarks"].back().second = confirmed;
  estimate_.diagnostics["num_tentative"].back().second = static_cast<double>(tracks_.size()) - confirmed;
  if (estimate_.trajectory.back().t_s == t_s) {
    estimate_.trajectory.back().pose = state_.Pose();
    estimate_.trajectory.back().covariance = state_.covariance.topLeftCorner<3, 3>();
  }
}

void EkfSlam::ContinueClosureTest(const LandmarkEvent& event) {
  EkfSlam& rival = closure_rival_.front();
  rival.ProcessLandmarks(event);
  closure_log_ratio_ += scan_log_likelihood_ - rival.scan_log_likelihood_;
  if (closure_log_ratio_ >= wald_.log_confirm) EndClosureTest(true, event.t_s);
  else if (closure_log_ratio_ <= wald_.log_delete) EndClosureTest(false, event.t_s);
  else Record(event.t_s, "closure_test_log_ratio", closure_log_ratio_);
}

void EkfSlam::EndClosureTest(bool keep_closure, double t_s) {
  const double log_ratio = closure_log_ratio_;
  if (!keep_closure) {
    const int fork = fork_scan_;
    EkfSlam rival = std::move(closure_rival_.front());
    rival.blocks_closures_ = false;
    *this = std::move(rival);  // its own history, from the fork on without the closure
    revised_from_scan_ = fork;  // its keys there may name other landmarks (both numbered from one counter)
  }
  closure_rival_.clear();
  closure_log_ratio_ = 0.0;
  test_fake_density_ = -1.0;
  Record(t_s, "closure_test_log_ratio", log_ratio);
  Record(t_s, "closure_kept", keep_closure ? 1.0 : 0.0);
}

double EkfSlam::FakeDensity() const {
  // What else a gate may hold: clutter, or a landmark not mapped yet. Unlike clutter, an
  // unmapped landmark repeats scan after scan, so the held pairings (which wait for
  // repeats) count only clutter; the closure test, which weighs whole scans, counts both.
  // While a test runs, both branches use the density at its fork: it is a property of the
  // world, not of either hypothesis. (Each branch's own births would favour the branch
  // without the closure, which maps every re-observation anew: the more it creates, the
  // more detections its density calls new, the likelier its scans.)
  if (test_fake_density_ >= 0.0) return test_fake_density_;
  return clutter_density_per_m2_ + NewLandmarkDensity();
}

double EkfSlam::ScanLogLikelihoodOf(const std::vector<Eigen::Vector2d>& z) const {
  std::vector<double> p_detect(tracks_.size());
  const SE2 pose = state_.Pose();
  for (size_t j = 0; j < tracks_.size(); ++j) {
    const double range_m = PredictObservation(pose, state_.Landmark(static_cast<int>(j))).z.x();
    const double p_band = config_.estimate_detection_rate ? DetectionProbability(detection_, range_m) : 1.0;
    p_detect[j] = p_band / (1.0 + std::exp(-tracks_[j].log_ratio));  // times the probability that it exists
  }
  return ScanLogLikelihood(state_, z, R_, p_detect,
                           {FakeDensity(), range_max_m_, half_fov_rad_});
}

}  // namespace slambox
