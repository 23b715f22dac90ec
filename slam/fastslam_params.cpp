// `fastslam1` / `fastslam2` parameters: names, units and meanings (`slambox algorithms
// --params fastslam2`, `--set algo.fastslam2.NAME=V`); the values are FastSlamConfig's.
#include "slam/fastslam.hpp"

namespace slambox {

void BindParams(FastSlamConfig& c, ParamBinder& b) {
  b.Bind("particles", c.particles, "-", "number of particles M");
  b.Bind("seed_offset", c.seed_offset, "-",
         "added to the stream's seed for this module's random draws: another run of the same filter on the same data "
         "(0: the stream's own draw)");
  static const EnumNames<NewLandmarkP0> kP0Names = {{NewLandmarkP0::kDensity, "density"},
                                                     {NewLandmarkP0::kGate, "gate"}};
  b.Bind("new_landmark_p0", c.new_landmark_p0, kP0Names,
         "p0, below which an observation starts a landmark: the density of clutter and unmapped landmarks "
         "(clutter_per_scan, births so far) | N(innovation at new_landmark_gate_chi2; 0, R)");
  b.Bind("new_landmark_gate_chi2", c.new_landmark_gate_chi2, "chi2",
         "new_landmark_p0=gate: p0 = N(innovation at this squared Mahalanobis distance; 0, R)");
  b.Bind("neff_threshold", c.neff_threshold, "fraction of M", "resample when N_eff < neff_threshold * M");
  b.Bind("use_known_ids", c.use_known_ids, "-", "associate by the detector's ids when the stream has them");
  b.Bind("visibility_margin_m", c.visibility_margin_m, "m",
         "existence counters: a landmark should have been seen within range_max - margin");
  b.Bind("candidate_margin_m", c.candidate_margin_m, "m", "association candidates lie within range_max + margin");
  b.Bind("report_min_counter", c.report_min_counter, "-", "unknown ids: report landmarks whose counter reached this");
  b.Bind("keep_confirmed", c.keep_confirmed, "-",
         "unknown ids, existence=counts: misses do not bring a reported landmark last seen more than 8 range_max of "
         "travel ago below report_min_counter (it stays mapped for a revisit to be matched against)");
  static const EnumNames<DetectionRateUse> kRateNames = {
      {DetectionRateUse::kAuto, "auto"}, {DetectionRateUse::kAlways, "true"}, {DetectionRateUse::kNever, "false"}};
  b.Bind("estimate_detection_rate", c.estimate_detection_rate, kRateNames,
         "unknown ids: a miss in view costs the counter P_D at its range (per band, over the best particle's "
         "reported landmarks, the sensor's detection_prob as prior) instead of 1; auto: where the stream does "
         "not state its P_D (detection_prob_known false: converted logs)");
  b.Bind("detection_rate_bands", c.detection_rate_bands, "bands", "range bands of the detection probability estimate");
  static const EnumNames<FastSlamExistence> kExistenceNames = {{FastSlamExistence::kAuto, "auto"},
                                                                {FastSlamExistence::kCounts, "counts"},
                                                                {FastSlamExistence::kSequentialTest, "sprt"}};
  b.Bind("existence", c.existence, kExistenceNames,
         "unknown ids: counts (+1 per sighting, -1 or -P_D per miss in view) | sprt (Wald's test of real against "
         "clutter in the pairing's gate, as ekf-slam's; reports landmarks it confirmed) | auto: sprt where the "
         "stream does not state its P_D (detection_prob_known false: converted logs), else counts");
  b.Bind("existence_error_prob", c.existence_error_prob, "-",
         "existence=sprt: probability of confirming a phantom and of deleting a real landmark (Wald's bounds)");
  b.Bind("motion_noise_scale", c.motion_noise_scale, "-", "factor on the odometry model's covariance");
  b.Bind("constellation_merges", c.constellation_merges, "-",
         "unknown ids: recognize a revisit mapped a second time by the shape of its landmarks (the best particle's "
         "map, slam/constellation_revisit.hpp); each particle then moves by its fit and merges the pairs");
  b.Bind("constellation_max_hypotheses", c.constellation_max_hypotheses, "hypotheses",
         "constellation_merges: search budget; windows whose pairs of equal length make more motions than this "
         "are not searched");
  b.Bind("constellation_gate_prob", c.constellation_gate_prob, "-",
         "constellation_merges: probability of the heading and tolerance gates; 1 - it bounds a false match");
  b.Bind("constellation_spread", c.constellation_spread, "-",
         "constellation_merges: the particle's path since the matched old ones relaxes under its motion within dead "
         "reckoning's drift model, and every landmark seen since moves as the path did where it was last seen "
         "(slam/fastslam_closure.hpp); the output path follows; off: only the window moves");
  b.Bind("closure_spread", c.closure_spread, "-",
         "known ids: a particle that re-observes landmarks last seen beyond the revisit search's widest window with an "
         "innovation its pose prior cannot explain moves to the pose that explains them under dead reckoning's "
         "drift; its path since them relaxes and the landmarks seen since follow (slam/fastslam_closure.hpp)");
  b.Bind("snapshot_period_s", c.snapshot_period_s, "s", "particle snapshots for figures (0 = none)");
  static const EnumNames<FastSlamTrajectory> kTrajectoryNames = {{FastSlamTrajectory::kBest, "best"},
                                                                  {FastSlamTrajectory::kMean, "mean"},
                                                                  {FastSlamTrajectory::kPathMean, "path_mean"}};
  b.Bind("trajectory", c.trajectory, kTrajectoryNames,
         "best particle's path | filtered weighted mean | weighted mean of the final particles' paths");
}
void BindParams(FastSlam2Config& c, ParamBinder& b) { BindParams(static_cast<FastSlamConfig&>(c), b); }

}  // namespace slambox
