// Landmark merging and existence in EKF-SLAM: the difference test against a hand-computed
// d^2, the merge against a dense Kalman conditioning, and on scripted detections (a robot
// standing still, so the only uncertainty is the sensor's): a duplicate merged, two trees
// closer than the sensor resolves never merged, the nearer of two twins merged first, a
// confirmed landmark removed by its existence count, clutter alone never confirmed.
#include "slam/landmark_merge.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <random>

#include "core/chi_square.hpp"
#include "core/error.hpp"
#include "slam/ekf_slam.hpp"

namespace slambox {
namespace {

EkfSlamState TwoLandmarkState() {
  EkfSlamState s;
  s.mean.resize(7);
  s.mean << 0.5, -0.2, 0.1, 1.0, 0.0, 1.3, 0.4;
  s.covariance = Eigen::MatrixXd::Zero(7, 7);
  s.covariance.block<2, 2>(3, 3) = Eigen::Vector2d(0.04, 0.09).asDiagonal();
  s.covariance.block<2, 2>(5, 5) = Eigen::Vector2d(0.01, 0.01).asDiagonal();
  s.covariance(3, 5) = s.covariance(5, 3) = 0.01;
  return s;
}

TEST(LandmarkMerge, DifferenceChi2IsTheHandComputedValue) {
  // C = P_aa + P_bb - P_ab - P_ba = diag(0.04 + 0.01 - 0.02, 0.09 + 0.01) = diag(0.03, 0.10),
  // D = (-0.3, -0.4): d^2 = 0.09 / 0.03 + 0.16 / 0.10 = 4.6.
  const EkfSlamState s = TwoLandmarkState();
  EXPECT_NEAR(LandmarkDifferenceChi2(s, 0, 1), 4.6, 1e-12);
  EXPECT_NEAR(LandmarkDifferenceChi2(s, 1, 0), 4.6, 1e-12);
}

TEST(LandmarkMerge, IndependentLandmarksFuseByInformation) {
  EkfSlamState s = TwoLandmarkState();
  s.covariance(3, 5) = s.covariance(5, 3) = 0.0;
  const Eigen::Matrix2d Pa = s.LandmarkCovariance(0), Pb = s.LandmarkCovariance(1);
  const Eigen::Matrix2d fused_cov = (Pa.inverse() + Pb.inverse()).inverse();
  const Eigen::Vector2d fused = fused_cov * (Pa.inverse() * s.Landmark(0) + Pb.inverse() * s.Landmark(1));
  ASSERT_TRUE(MergeLandmarks(s, 0, 1));
  ASSERT_EQ(s.NumLandmarks(), 1);
  EXPECT_LT((s.Landmark(0) - fused).norm(), 1e-12);
  EXPECT_LT((s.LandmarkCovariance(0) - fused_cov).norm(), 1e-12);
  EXPECT_EQ(s.Pose().vector(), Eigen::Vector3d(0.5, -0.2, 0.1));  // uncorrelated robot untouched
}

TEST(LandmarkMerge, CorrelatedStateMatchesDenseConditioning) {
  // Random SPD covariance over robot + 3 landmarks; merge landmark 2 into 0 and compare
  // with x' = x - P H^T (H P H^T)^-1 H x, P' = P - P H^T (H P H^T)^-1 H P, then drop rows of 2.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01;
  const int n = 9;
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = n01(rng);
  EkfSlamState s;
  s.covariance = 0.1 * A * A.transpose() + 0.01 * Eigen::MatrixXd::Identity(n, n);
  s.mean = Eigen::VectorXd(n);
  for (int i = 0; i < n; ++i) s.mean(i) = n01(rng);
  s.mean(2) = 0.3;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, n);
  H.block<2, 2>(0, 3).setIdentity();
  H.block<2, 2>(0, 7) = -Eigen::Matrix2d::Identity();
  const Eigen::MatrixXd S = H * s.covariance * H.transpose();
  const Eigen::MatrixXd K = s.covariance * H.transpose() * S.inverse();
  const Eigen::VectorXd x = s.mean - K * (H * s.mean);
  const Eigen::MatrixXd P = s.covariance - K * H * s.covariance;
  ASSERT_TRUE(MergeLandmarks(s, 0, 2));
  ASSERT_EQ(s.mean.size(), 7);
  EXPECT_LT((s.mean - x.head(7)).norm(), 1e-10);
  EXPECT_LT((s.covariance - P.topLeftCorner(7, 7)).norm(), 1e-10);
  EXPECT_TRUE(s.covariance == s.covariance.transpose());
}

TEST(LandmarkMerge, WrapsTheRobotHeading) {
  EkfSlamState s = TwoLandmarkState();
  s.mean(2) = M_PI - 1e-3;
  s.covariance(2, 2) = 1.0;
  s.covariance(2, 3) = s.covariance(3, 2) = 0.15;  // the merge pulls theta up through +pi
  ASSERT_TRUE(MergeLandmarks(s, 0, 1));
  EXPECT_GE(s.mean(2), -M_PI);
  EXPECT_LT(s.mean(2), M_PI);
  EXPECT_LT(s.mean(2), 0.0);
}

// --- scripted detections: a robot standing at the origin, no odometry -------------------

struct Scripted {
  explicit Scripted(const EkfSlamConfig& config, double sigma_bearing_deg = 1.0, double clutter_per_scan = 0.0)
      : ekf(config) {
    StreamHeader header;
    LandmarkSensorConfig sensor;
    sensor.known_ids = false;
    sensor.sigma_range_m = 0.1;
    sensor.sigma_bearing_deg = sigma_bearing_deg;
    sensor.range_max_m = 15.0;
    sensor.clutter_per_scan = clutter_per_scan;
    header.sensors.landmarks = sensor;
    ekf.Start(header);
  }
  void Scan(std::vector<LandmarkObservation> obs) { ekf.OnLandmarks({0.1 * ++scans, std::move(obs)}); }
  int Confirmed() const {
    int n = 0;
    for (const auto& t : ekf.tracks()) n += t.confirmed ? 1 : 0;
    return n;
  }
  EkfSlam ekf;
  int scans = 0;
};

TEST(EkfSlamExistence, DuplicateOutsideTheNewLandmarkGateIsMerged) {
  // Tiny gates force a second landmark from the second sighting: d^2 = 0.15^2 / (2 * 0.1^2)
  // = 1.125 > gate_new 1.0. The two are statistically identical (the same d^2 < 9.21) and
  // were never seen together, so they merge into their information-weighted mean.
  Scripted s({.gate_accept_chi2 = 0.5, .gate_new_chi2 = 1.0});
  s.Scan({{5.0, 0.0, -1}});
  ASSERT_EQ(s.ekf.tracks().size(), 1u);
  s.Scan({{5.15, 0.0, -1}});
  ASSERT_EQ(s.ekf.tracks().size(), 1u);
  EXPECT_EQ(s.ekf.ResolveKey(1), 0);
  EXPECT_EQ(s.ekf.next_key(), 2);  // key 1 is gone from tracks() but still resolves: never free again
  EXPECT_NEAR(s.ekf.state().Landmark(0).x(), 5.075, 1e-9);
  EXPECT_NEAR(s.ekf.state().Landmark(0).y(), 0.0, 1e-12);
  EXPECT_EQ(s.ekf.tracks()[0].sightings, 2);
  s.Scan({{5.075, 0.0, -1}});
  EXPECT_EQ(s.Confirmed(), 1);
  const Estimate e = s.ekf.Finish();
  ASSERT_EQ(e.landmarks.size(), 1u);
  double merged = 0;
  for (const auto& [t, m] : e.diagnostics.at("merged_landmarks")) merged += m;
  EXPECT_EQ(merged, 1.0);
}

TEST(EkfSlamExistence, TheMostSimilarOfTwoDuplicatesIsMerged) {
  // Landmark 0 at 5 m; then two new ones in one scan (so never the same tree), listed
  // farther first: at 5.3 m (difference d^2 4.5) and 5.15 m (d^2 1.125), both outside the
  // new gate 1.0 and inside the merge gate 9.21. The nearer twin is merged (forest seed
  // 218: merging the first pair found took a neighbouring tree); the other then shares a
  // scan with the merged landmark and stays.
  Scripted s({.gate_accept_chi2 = 0.5, .gate_new_chi2 = 1.0, .closure_test = false});
  s.Scan({{5.0, 0.0, -1}});
  s.Scan({{5.3, 0.0, -1}, {5.15, 0.0, -1}});
  ASSERT_EQ(s.ekf.tracks().size(), 2u);
  EXPECT_EQ(s.ekf.ResolveKey(2), 0);  // 5.15 m into the first landmark
  EXPECT_EQ(s.ekf.ResolveKey(1), 1);
  EXPECT_NEAR(s.ekf.state().Landmark(0).x(), 5.075, 1e-9);
  EXPECT_NEAR(s.ekf.state().Landmark(1).x(), 5.3, 1e-9);
}

TEST(EkfSlamExistence, TwoTreesCloserThanTheSensorResolvesAreNeverMerged) {
  // Two trees 0.3 m apart at 10 m (bearing 0.03 rad apart, sigma 3 deg = 0.052 rad): seen
  // in every scan, each observation goes to its own landmark. Their difference is
  // statistically zero (checked below), so only "seen in one scan" keeps them apart.
  Scripted s({}, 3.0);
  for (int k = 0; k < 20; ++k) s.Scan({{10.0, 0.0, -1}, {10.0, 0.03, -1}});
  ASSERT_EQ(s.ekf.tracks().size(), 2u);
  EXPECT_EQ(s.Confirmed(), 2);
  EXPECT_LT(LandmarkDifferenceChi2(s.ekf.state(), 0, 1), ChiSquareQuantile(0.99, 2.0));
  EXPECT_LT((s.ekf.state().Landmark(1) - s.ekf.state().Landmark(0)).norm(), 0.5);
  const Estimate e = s.ekf.Finish();
  for (const auto& [t, m] : e.diagnostics.at("merged_landmarks")) EXPECT_EQ(m, 0.0);
}

TEST(EkfSlamExistence, ConfirmedLandmarkIsRemovedWhenItsCountReachesZero) {
  // Seen 3 times (confirmed, existence 3), then missed in view: 2, 1, 0 -> removed (each
  // miss costs 1: the configured P_D, not the estimate, which the next test covers). The
  // count rule (tentative_ and confirmed_existence=counts; the default sprt:
  // tests/slam/landmark_existence_test.cpp).
  Scripted s({.tentative_existence = ExistenceRule::kCounts, .confirmed_existence = ExistenceRule::kCounts,
              .estimate_detection_rate = false});
  for (int k = 0; k < 3; ++k) s.Scan({{5.0, 0.0, -1}});
  ASSERT_EQ(s.Confirmed(), 1);
  EXPECT_EQ(s.ekf.tracks()[0].existence, 3);
  s.Scan({});
  s.Scan({});
  ASSERT_EQ(s.Confirmed(), 1);
  EXPECT_EQ(s.ekf.tracks()[0].existence, 1);
  s.Scan({});
  EXPECT_EQ(s.ekf.tracks().size(), 0u);
  // Out of range it is not expected, so it is not missed.
  Scripted far({.tentative_existence = ExistenceRule::kCounts, .confirmed_existence = ExistenceRule::kCounts});
  for (int k = 0; k < 3; ++k) far.Scan({{14.8, 0.0, -1}});
  for (int k = 0; k < 10; ++k) far.Scan({});
  EXPECT_EQ(far.Confirmed(), 1);
}

TEST(EkfSlamExistence, SeenOnlyNearRangeMaxIsConfirmedBySightings) {
  // 14.8 m is inside range_max (15) but not visibility_margin_m (0.5) inside it: not
  // expected in view, so its absence is no miss; its detections are still evidence. With
  // the sequential test (the default) and no clutter configured, prior log 2 + 50 at the
  // 2nd sighting confirms (before detections out of view counted, it was never tried and
  // expired after tentative_max_age_s: a post seen only near range_max on `landmarks`).
  Scripted s({});
  s.Scan({{14.8, 0.0, -1}});
  EXPECT_EQ(s.Confirmed(), 0);
  s.Scan({{14.8, 0.0, -1}});
  EXPECT_EQ(s.Confirmed(), 1);
  for (int k = 0; k < 30; ++k) s.Scan({});  // 3 s > tentative_max_age_s, not expected in view
  EXPECT_EQ(s.Confirmed(), 1);
  ASSERT_EQ(s.ekf.tracks().size(), 1u);
}

TEST(EkfSlamExistence, MissCostsTheMeasuredDetectionRate) {
  // A miss costs min(1, P_band x (detected + 1) / (expected + 1)): P_band the confirmed
  // landmarks' rate at that range, (seen + P_D) / (expected + 1) with the sensor's P_D = 1
  // as prior; detected / expected this landmark's sightings and the sum of P_band over its
  // scans in view (each starting at 1 for the scan that created it). Seen in scans 1-3
  // (confirmed at 3): miss 1 costs 1 x 4 / 4; a sighting (P_band 1/2); miss 2 costs
  // P_band = 2/3 times (4 + 1) / (4.5 + 1). (The count rules, tentative_ and confirmed_existence=counts.)
  Scripted s({.tentative_existence = ExistenceRule::kCounts, .confirmed_existence = ExistenceRule::kCounts});
  for (int k = 0; k < 3; ++k) s.Scan({{5.0, 0.0, -1}});
  EXPECT_DOUBLE_EQ(s.ekf.tracks()[0].existence, 3.0);
  s.Scan({});
  EXPECT_DOUBLE_EQ(s.ekf.tracks()[0].existence, 2.0);
  s.Scan({{5.0, 0.0, -1}});
  EXPECT_DOUBLE_EQ(s.ekf.tracks()[0].existence, 3.0);
  s.Scan({});
  EXPECT_NEAR(s.ekf.tracks()[0].existence, 3.0 - 2.0 / 3.0 * 5.0 / 5.5, 1e-12);
  // Seen every other scan (as often as P_band says) it gains +1 - ~1/2 per pair and
  // survives three misses in a row; at a cost of 1 per miss its count would stay at 2 and
  // two misses would remove it.
  Scripted unit({.tentative_existence = ExistenceRule::kCounts, .confirmed_existence = ExistenceRule::kCounts,
                 .estimate_detection_rate = false});
  for (Scripted* x : {&s, &unit}) {
    if (x == &unit) {
      for (int k = 0; k < 3; ++k) unit.Scan({{5.0, 0.0, -1}});
      unit.Scan({});
      unit.Scan({{5.0, 0.0, -1}});
      unit.Scan({});
    }
    for (int k = 0; k < 40; ++k)
      x->Scan(k % 2 ? std::vector<LandmarkObservation>{{5.0, 0.0, -1}} : std::vector<LandmarkObservation>{});
    for (int k = 0; k < 3; ++k) x->Scan({});
  }
  EXPECT_EQ(s.Confirmed(), 1);
  EXPECT_GT(s.ekf.tracks()[0].existence, 3.0);
  EXPECT_EQ(unit.ekf.tracks().size(), 0u);
}

TEST(EkfSlamExistence, TentativeLandmarkIsRemovedAfterItsMisses) {
  // tentative_existence=counts: tentative_max_misses = 3 (the sequential test's deletion:
  // tests/slam/landmark_existence_test.cpp, TentativeIsDeletedAtTheThirdMiss).
  Scripted s({.tentative_existence = ExistenceRule::kCounts});
  s.Scan({{5.0, 0.0, -1}});
  s.Scan({});
  s.Scan({});
  ASSERT_EQ(s.ekf.tracks().size(), 1u);
  s.Scan({});
  EXPECT_EQ(s.ekf.tracks().size(), 0u);
}

TEST(EkfSlamExistence, ClutterAloneIsNeverConfirmed) {
  // 1000 scans of Poisson(1) false detections uniform over the 15 m disc, declared in the
  // header (the sequential test, the default, takes its clutter rate from there); both rules.
  for (const ExistenceRule rule : {ExistenceRule::kSequentialTest, ExistenceRule::kCounts}) {
    Scripted s({.tentative_existence = rule}, 1.0, 1.0);
    std::mt19937_64 rng(3);
    std::poisson_distribution<int> count(1.0);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int confirmed_ever = 0;
    for (int k = 0; k < 1000; ++k) {
      std::vector<LandmarkObservation> obs;
      for (int i = count(rng); i > 0; --i) obs.push_back({15.0 * std::sqrt(u(rng)), M_PI * (2 * u(rng) - 1), -1});
      s.Scan(obs);
      confirmed_ever = std::max(confirmed_ever, s.Confirmed());
    }
    EXPECT_EQ(confirmed_ever, 0) << NameOf(ExistenceRuleNames(), rule);
    EXPECT_TRUE(s.ekf.Finish().landmarks.empty()) << NameOf(ExistenceRuleNames(), rule);
  }
}

TEST(EkfSlamExistence, BadSettingsAreInputErrors) {
  EXPECT_THROW(EkfSlam({.merge_probability = 1.0}), InputError);
  EXPECT_THROW(EkfSlam({.merge_probability = -0.1}), InputError);
  EXPECT_THROW(EkfSlam({.tentative_max_age_s = 0.0}), InputError);
  EXPECT_NO_THROW(EkfSlam({.merge_probability = 0.0}));
}

}  // namespace
}  // namespace slambox
