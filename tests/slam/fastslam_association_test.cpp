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
