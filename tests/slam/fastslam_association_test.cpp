// Data association against p0 and the existence counters of one FastSLAM particle
// (Thrun, Prob. Robotics, Table 13.2).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

#include "slam/fastslam_particle.hpp"
#include "slam/landmark_ekf.hpp"

namespace slambox {
namespace {

ParticleUpdateOptions UnknownIds(bool fastslam2 = false) {
  ParticleUpdateOptions o;
  o.R = Eigen::Vector2d(0.05 * 0.05, 0.02 * 0.02).asDiagonal();
  o.fastslam2 = fastslam2;
  o.known_ids = false;
  o.range_max_m = 10.0;
  o.half_fov_rad = M_PI / 2;  // 180 degree field of view, looking along +x
  o.visibility_margin_m = 0.5;
  return o;
}

FastSlamParticle ParticleWith(const std::vector<Eigen::Vector2d>& landmarks, int counter = 5) {
  FastSlamParticle p;
  for (const auto& m : landmarks) {
    LandmarkGaussian lm;
    lm.mean = m;
    lm.covariance = Eigen::Matrix2d::Identity() * 0.01;
    lm.counter = counter;
    SetLandmark(p.map, p.next_key++, lm);
  }
  return p;
}

LandmarkObservation Obs(double r, double b) { return {r, b, -1}; }

// new_landmark_p0=density: p0 at range r is fake_density_per_m2 * r (dx dy = r dr db), the
// range held at sigma_range or more; without a density, the constant log_p0.
TEST(FastSlamAssociation, DensityP0IsTheFakeDensityTimesTheRange) {
  ParticleUpdateOptions o = UnknownIds();
  o.log_p0 = -7.5;
  EXPECT_EQ(o.LogP0(5.0), -7.5);
  o.fake_density_per_m2 = 2e-3;
  EXPECT_DOUBLE_EQ(o.LogP0(5.0), std::log(1e-2));
  EXPECT_DOUBLE_EQ(o.LogP0(0.0), std::log(2e-3 * 0.05));  // sigma_range = 0.05 m

  // The decision and the weight factor follow the density: just above the likelihood a
  // new landmark at p0, just below a match.
  const FastSlamParticle start = ParticleWith({{5, 0}, {0, 6}});
  const LandmarkObservation z = Obs(5.2, 0.03);
  const double ll = MeasureLandmark(start.pose, *FindLandmark(start.map, 0), {z.range_m, z.bearing_rad}, o.R).log_likelihood;
  std::mt19937_64 rng(1);
  o.fake_density_per_m2 = std::exp(ll + 1e-9) / 5.2;
  FastSlamParticle a = start;
  const ParticleUpdateSummary sa = UpdateParticle(a, {z}, o, rng);
  EXPECT_EQ(sa.created, 1);
  EXPECT_NEAR(sa.log_weight_factor, ll + 1e-9, 1e-12);
  o.fake_density_per_m2 = std::exp(ll - 1e-9) / 5.2;
  FastSlamParticle b = start;
  const ParticleUpdateSummary sb = UpdateParticle(b, {z}, o, rng);
  EXPECT_EQ(sb.matched, 1);
  EXPECT_EQ(sb.created, 0);
}

// One landmark; the observation's likelihood is ll. With p0 just above ll a new
// landmark is created and the weight factor is p0; just below, the landmark is matched
// and the factor is ll.
TEST(FastSlamAssociation, NewLandmarkExactlyWhenEveryLikelihoodIsBelowP0) {
  for (bool fs2 : {false, true}) {
    const FastSlamParticle start = ParticleWith({{5, 0}, {0, 6}});
    const LandmarkObservation z = Obs(5.2, 0.03);
    double ll = MeasureLandmark(start.pose, *FindLandmark(start.map, 0), {z.range_m, z.bearing_rad},
                                UnknownIds().R).log_likelihood;
    std::mt19937_64 rng(1);
    ParticleUpdateOptions o = UnknownIds(fs2);

    o.log_p0 = ll + 1e-9;
    FastSlamParticle a = start;
    const ParticleUpdateSummary sa = UpdateParticle(a, {z}, o, rng);
    EXPECT_EQ(sa.created, 1);
    EXPECT_EQ(sa.matched, 0);
    EXPECT_EQ(a.map.size, 3);
    EXPECT_DOUBLE_EQ(sa.log_weight_factor, o.log_p0);
    ASSERT_NE(FindLandmark(a.map, 2), nullptr);
    EXPECT_NEAR(FindLandmark(a.map, 2)->mean.x(), 5.2 * std::cos(0.03), 1e-12);
    EXPECT_EQ(FindLandmark(a.map, 0)->mean, Eigen::Vector2d(5, 0));  // untouched

    o.log_p0 = ll - 1e-9;
    FastSlamParticle b = start;
    const ParticleUpdateSummary sb = UpdateParticle(b, {z}, o, rng);
    EXPECT_EQ(sb.created, 0);
    EXPECT_EQ(sb.matched, 1);
    EXPECT_EQ(b.map.size, 2);
    EXPECT_DOUBLE_EQ(sb.log_weight_factor, ll);  // zero prior covariance: 2.0's L equals Q
    EXPECT_GT(FindLandmark(b.map, 0)->mean.x(), 5.0);  // pulled towards the measurement
    EXPECT_EQ(FindLandmark(b.map, 0)->counter, 6);
    // the other particle's map (start) is unchanged by either update
    EXPECT_EQ(FindLandmark(start.map, 0)->mean, Eigen::Vector2d(5, 0));
    EXPECT_EQ(FindLandmark(start.map, 0)->counter, 5);
  }
}

TEST(FastSlamAssociation, TwoObservationsNeverShareOneLandmark) {
  FastSlamParticle p = ParticleWith({{5, 0}});
  ParticleUpdateOptions o = UnknownIds();
  o.log_p0 = -50;  // everything would match
  std::mt19937_64 rng(1);
  const ParticleUpdateSummary s = UpdateParticle(p, {Obs(5.3, 0.0), Obs(5.01, 0.0)}, o, rng);
  EXPECT_EQ(s.matched, 1);
  EXPECT_EQ(s.created, 1);
  // the closer observation won the match; the other became landmark 1
  EXPECT_NEAR(FindLandmark(p.map, 1)->mean.x(), 5.3, 1e-12);
}

// A false detection starts with counter 1; each scan where it should have been seen
// but was not takes one off; below zero it is gone: exactly after the second miss.
TEST(FastSlamAssociation, FalseDetectionIsRemovedAfterTwoMisses) {
  ParticleUpdateOptions o = UnknownIds();
  o.log_p0 = -std::log(2 * M_PI) - 0.5 * std::log(o.R.determinant()) - 0.5 * 13.8;
  FastSlamParticle p = ParticleWith({{5, 0}, {3, 3}});
  std::mt19937_64 rng(1);
  UpdateParticle(p, {Obs(5, 0), Obs(4, -0.5)}, o, rng);  // second one: clutter
  ASSERT_EQ(p.map.size, 3);
  EXPECT_EQ(FindLandmark(p.map, 2)->counter, 1);
  const std::vector<LandmarkObservation> real = {Obs(5, 0), Obs(std::sqrt(18.0), M_PI / 4)};
  ParticleUpdateSummary s = UpdateParticle(p, real, o, rng);
  EXPECT_EQ(s.discarded, 0);
  EXPECT_EQ(FindLandmark(p.map, 2)->counter, 0);
  s = UpdateParticle(p, real, o, rng);
  EXPECT_EQ(s.discarded, 1);
  EXPECT_EQ(FindLandmark(p.map, 2), nullptr);
  EXPECT_EQ(p.map.size, 2);
  EXPECT_EQ(FindLandmark(p.map, 0)->counter, 8);  // 5 + 3 sightings
}

TEST(FastSlamAssociation, CountersSkipLandmarksThatCouldNotHaveBeenSeen) {
  ParticleUpdateOptions o = UnknownIds();
  o.log_p0 = -10;
  // behind the robot (outside the 180 deg field of view), beyond range, and inside the
  // visibility margin at the edge of range: none may lose a count
  FastSlamParticle p = ParticleWith({{-3, 0}, {10.5, 0}, {0, 9.7}, {4, 0}}, 0);
  std::mt19937_64 rng(1);
  const ParticleUpdateSummary s = UpdateParticle(p, {}, o, rng);
  EXPECT_EQ(s.discarded, 1);  // only (4, 0), in full view
  EXPECT_EQ(p.map.size, 3);
  EXPECT_EQ(FindLandmark(p.map, 3), nullptr);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(FindLandmark(p.map, k)->counter, 0) << k;
}

// estimate_detection_rate: a miss in view costs P_D at the landmark's range. With the
// configured probability 1 as prior, P_D is 0.5 in the band of (4, 0) (one of three
// expected scans seen: (1 + 1) / (3 + 1)) and 1 in the empty band of (6, 0). The landmark
// at (4, 0) with counter 0.5 survives its first miss (0) and goes at the second (-0.5; with
// the cost 1 it would go at the first); the confirmed one at (6, 0) is listed as expected,
// seen or not, and pays 1 when missed.
TEST(FastSlamAssociation, MissesCostTheDetectionProbabilityAtTheirRange) {
  ParticleUpdateOptions o = UnknownIds();
  o.log_p0 = -10;
  o.estimate_detection_rate = true;
  o.confirmed_counter = 10;
  o.detection = MakeDetectionRate(10.0, 10, 1.0);
  CountExpected(o.detection, 4.5, true);
  CountExpected(o.detection, 4.5, false);
  CountExpected(o.detection, 4.5, false);
  ASSERT_DOUBLE_EQ(DetectionProbability(o.detection, 4.0), 0.5);
  ASSERT_DOUBLE_EQ(DetectionProbability(o.detection, 6.0), 1.0);
  FastSlamParticle p = ParticleWith({{4, 0}, {6, 0}}, 10);
  LandmarkGaussian weak = *FindLandmark(p.map, 0);
  weak.counter = 0.5;
  SetLandmark(p.map, 0, weak);
  std::mt19937_64 rng(1);
  ParticleUpdateSummary s = UpdateParticle(p, {Obs(6, 0)}, o, rng);
  EXPECT_EQ(s.matched, 1);
  EXPECT_EQ(s.discarded, 0);
  EXPECT_DOUBLE_EQ(FindLandmark(p.map, 0)->counter, 0.0);
  EXPECT_DOUBLE_EQ(FindLandmark(p.map, 1)->counter, 11.0);
  ASSERT_EQ(s.expected.size(), 1u);  // (4, 0) is not confirmed
  EXPECT_NEAR(s.expected[0].first, 6.0, 0.05);
  EXPECT_TRUE(s.expected[0].second);
  s = UpdateParticle(p, {}, o, rng);
  EXPECT_EQ(s.discarded, 1);
  EXPECT_EQ(FindLandmark(p.map, 0), nullptr);
  EXPECT_DOUBLE_EQ(FindLandmark(p.map, 1)->counter, 10.0);
  ASSERT_EQ(s.expected.size(), 1u);
  EXPECT_FALSE(s.expected[0].second);
}

// keep_confirmed_unseen_m: a confirmed landmark (counter 10 = confirmed_counter) last seen 50 m
// of travel ago, missed in view, keeps its count and stays where the bound is 40 m; a tentative
// one (counter 3) loses one per miss and goes at its fourth; where the bound is 60 m (seen
// within it) the confirmed one goes at its eleventh miss.
TEST(FastSlamAssociation, ConfirmedLandmarksUnseenForLongOutlastTheirMisses) {
  for (const bool keep : {true, false}) {
    ParticleUpdateOptions o = UnknownIds();
    o.confirmed_counter = 10;
    o.travel_m = 50.0;
    o.keep_confirmed_unseen_m = keep ? 40.0 : 60.0;
    FastSlamParticle p = ParticleWith({{4, 0}, {6, 0}}, 10);
    LandmarkGaussian tentative = *FindLandmark(p.map, 0);
    tentative.counter = 3;
    SetLandmark(p.map, 0, tentative);
    std::mt19937_64 rng(1);
    int discarded = 0;
    for (int miss = 1; miss <= 11; ++miss) {
      discarded += UpdateParticle(p, {}, o, rng).discarded;
      if (miss == 3) EXPECT_NE(FindLandmark(p.map, 0), nullptr);
      if (miss == 4) EXPECT_EQ(FindLandmark(p.map, 0), nullptr);
      if (miss == 10) ASSERT_NE(FindLandmark(p.map, 1), nullptr);
    }
    if (keep) {
      EXPECT_EQ(discarded, 1);
      ASSERT_NE(FindLandmark(p.map, 1), nullptr);
      EXPECT_DOUBLE_EQ(FindLandmark(p.map, 1)->counter, 10.0);
    } else {
      EXPECT_EQ(discarded, 2);
      EXPECT_EQ(FindLandmark(p.map, 1), nullptr);
    }
  }
}

// existence=sprt (ParticleUpdateOptions::existence): one scan from the origin sees the
// landmark at (6, 0), misses the one at (4, 0) in full view and starts a new one. Each
// trial's gate is where N(z; z_hat, L) >= p0: with zero pose covariance and landmark
// covariance 0.01 I, L = diag(0.01 + s_r^2, 0.01 / r^2 + s_b^2) (range row (1, 0), bearing
// row (0, 1 / r) along +x), g = 2 (log N(z_hat; z_hat, L) - log p0), P_G = 1 - exp(-g / 2),
// mu = density pi g sqrt(det L) r; a sighting adds log(P_D P_G / (1 - exp(-mu))), a miss
// log((1 - P_D P_G) / exp(-mu)). Counters count sightings only; the missed landmark goes
// at its third miss (0 -> -1.60 -> -3.19 -> -4.79 <= log(0.01 / 0.99) = -4.60).
TEST(FastSlamAssociation, SequentialTestWeighsTrialsByDetectionAndClutterInTheGate) {
  ParticleUpdateOptions o = UnknownIds();
  o.log_p0 = -10;
  o.existence = ExistenceRule::kSequentialTest;
  o.wald = MakeWaldThresholds(0.01, 0.01);
  o.detection = MakeDetectionRate(10.0, 1, 0.8);  // not estimated: P_D 0.8 at every range
  o.clutter_density_per_m2 = 0.01;
  o.new_log_ratio = 1.5;
  o.confirmed_counter = 6;
  FastSlamParticle p = ParticleWith({{4, 0}, {6, 0}}, 5);
  LandmarkGaussian earlier = *FindLandmark(p.map, 1);
  earlier.log_ratio = 1.0;  // a sighting before
  SetLandmark(p.map, 1, earlier);
  auto trial = [&](double r, bool detected) {
    const double det_L = (0.01 + 0.05 * 0.05) * (0.01 / (r * r) + 0.02 * 0.02);
    const double g = 2.0 * (-std::log(2 * M_PI) - 0.5 * std::log(det_L) - o.log_p0);
    const double p_gate = 1.0 - std::exp(-0.5 * g), mu = 0.01 * M_PI * g * std::sqrt(det_L) * r;
    return detected ? std::log(0.8 * p_gate / (1.0 - std::exp(-mu))) : std::log((1.0 - 0.8 * p_gate) / std::exp(-mu));
  };
  std::mt19937_64 rng(1);
  ParticleUpdateSummary s = UpdateParticle(p, {Obs(6, 0), Obs(3, -1.0)}, o, rng);
  EXPECT_EQ(s.matched, 1);
  EXPECT_EQ(s.created, 1);
  EXPECT_EQ(s.discarded, 0);
  EXPECT_NEAR(FindLandmark(p.map, 1)->log_ratio, 1.0 + trial(6.0, true), 1e-9);
  EXPECT_DOUBLE_EQ(FindLandmark(p.map, 1)->counter, 6.0);  // 5 + its sighting
  EXPECT_NEAR(FindLandmark(p.map, 0)->log_ratio, trial(4.0, false), 1e-9);
  EXPECT_DOUBLE_EQ(FindLandmark(p.map, 0)->counter, 5.0);  // a miss leaves the sightings
  EXPECT_DOUBLE_EQ(FindLandmark(p.map, 2)->log_ratio, 1.5);
  EXPECT_DOUBLE_EQ(FindLandmark(p.map, 2)->counter, 1.0);
  // Confirmed: enough sightings and the test's upper bound, log(0.99 / 0.01) = 4.60
  // (1 + 3.96, where the first sighting alone would not be).
  EXPECT_GT(1.0 + trial(6.0, true), o.wald.log_confirm);
  EXPECT_LT(trial(6.0, true), o.wald.log_confirm);
  EXPECT_TRUE(o.Confirmed(*FindLandmark(p.map, 1)));
  EXPECT_FALSE(o.Confirmed(*FindLandmark(p.map, 0)));  // 5 sightings, a negative ratio
  EXPECT_FALSE(o.Confirmed(*FindLandmark(p.map, 2)));
  s = UpdateParticle(p, {Obs(6, 0), Obs(3, -1.0)}, o, rng);
  EXPECT_EQ(s.discarded, 0);
  EXPECT_NEAR(FindLandmark(p.map, 0)->log_ratio, 2 * trial(4.0, false), 1e-9);
  s = UpdateParticle(p, {Obs(6, 0), Obs(3, -1.0)}, o, rng);
  EXPECT_EQ(s.discarded, 1);
  EXPECT_EQ(FindLandmark(p.map, 0), nullptr);
  EXPECT_LT(3 * trial(4.0, false), o.wald.log_delete);
  EXPECT_GT(2 * trial(4.0, false), o.wald.log_delete);
}

TEST(FastSlamAssociation, KnownIdsUseTheIdsAndIgnoreClutter) {
  ParticleUpdateOptions o = UnknownIds();
  o.known_ids = true;
  FastSlamParticle p;
  std::mt19937_64 rng(1);
  UpdateParticle(p, {{5, 0, 7}, {2, 0.1, -1}}, o, rng);
  EXPECT_EQ(p.map.size, 1);
  ASSERT_NE(FindLandmark(p.map, 7), nullptr);
  // far from its estimate but still associated by id; no counters in known-id mode
  const ParticleUpdateSummary s = UpdateParticle(p, {{6, 0.5, 7}}, o, rng);
  EXPECT_EQ(s.matched, 1);
  EXPECT_EQ(s.created, 0);
  EXPECT_EQ(FindLandmark(p.map, 7)->counter, 2);
}

TEST(FastSlamAssociation, FastSlam2ProposalPullsThePoseTowardsTheObservation) {
  ParticleUpdateOptions o = UnknownIds(true);
  o.log_p0 = -20;
  FastSlamParticle p = ParticleWith({{5, 0}});
  LandmarkGaussian sharp = *FindLandmark(p.map, 0);
  sharp.covariance = Eigen::Matrix2d::Identity() * 1e-6;
  SetLandmark(p.map, 0, sharp);
  p.pose_covariance = Eigen::Vector3d(0.04, 0.04, 0.001).asDiagonal();
  // the landmark is seen 0.3 m closer than predicted: the robot must be near x = 0.3
  std::mt19937_64 rng(5);
  double mean_x = 0;
  for (int i = 0; i < 200; ++i) {
    FastSlamParticle q = p;
    UpdateParticle(q, {Obs(4.7, 0.0)}, o, rng);
    mean_x += q.pose.x / 200;
    EXPECT_TRUE(q.pose_covariance.isZero());
  }
  // proposal mean x = 0.04 / (0.04 + 0.0025 + ~0) * 0.3 = 0.282; sd of the mean < 0.004
  EXPECT_NEAR(mean_x, 0.3 * 0.04 / (0.04 + 0.0025 + 1e-6), 0.015);
}

}  // namespace
}  // namespace slambox
