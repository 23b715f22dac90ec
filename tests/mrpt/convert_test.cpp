// Conversions at the MRPT edge: scans, odometry actions and bearing-range observations.
#include <gtest/gtest.h>

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPoseRandomSampler.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>

#include <cstring>
#include <random>

#include "slam/mrpt/mrpt_convert.hpp"
#include "tests/support/synthetic_scan.hpp"

namespace slambox {
namespace {

namespace mb = mrpt_bridge;

LaserScanEvent MakeScan(double angle_min_rad, double increment_rad, int beams, std::uint64_t seed) {
  LaserScanEvent s;
  s.t_s = 1.5;
  s.angle_min_rad = angle_min_rad;
  s.angle_increment_rad = increment_rad;
  s.range_min_m = 0.1;
  s.range_max_m = 20.0;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> range(0.5, 19.0);
  for (int i = 0; i < beams; ++i) {
    const bool valid = i % 7 != 3;  // some misses
    s.ranges_m.push_back(valid ? range(rng) : s.range_max_m);
    s.valid.push_back(valid ? 1 : 0);
  }
  return s;
}

std::vector<Eigen::Vector2d> OurPoints(const LaserScanEvent& s) {
  std::vector<Eigen::Vector2d> pts;
  for (size_t i = 0; i < s.ranges_m.size(); ++i) {
    if (!s.valid[i]) continue;
    const double a = s.angle_min_rad + static_cast<double>(i) * s.angle_increment_rad;
    pts.push_back(s.ranges_m[i] * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return pts;
}

void ExpectSamePointsThroughMrpt(const LaserScanEvent& scan, int grid_upsampling = 0) {
  const auto obs = grid_upsampling > 0 ? mb::ToMrptScanForGrid(scan, 0.01, grid_upsampling) : mb::ToMrptScan(scan, 0.01);
  EXPECT_TRUE(obs.rightToLeft);
  mrpt::maps::CSimplePointsMap map;
  map.insertionOptions.minDistBetweenLaserPoints = 0.0f;
  map.insertionOptions.also_interpolate = false;
  map.insertObservation(obs);  // MRPT's own beam geometry, robot at the origin
  const auto ours = OurPoints(scan);
  ASSERT_EQ(map.size(), ours.size());
  for (size_t i = 0; i < ours.size(); ++i) {
    float x, y;
    map.getPoint(i, x, y);
    // float ranges and aperture: 20 m * ~1e-7 rad ≈ a few µm
    EXPECT_NEAR(x, ours[i].x(), 2e-5) << "beam point " << i;
    EXPECT_NEAR(y, ours[i].y(), 2e-5) << "beam point " << i;
  }
}

TEST(MrptConvert, FullCircleScanGivesTheSamePointsInMrpt) {
  ExpectSamePointsThroughMrpt(MakeScan(-M_PI, 2 * M_PI / 360, 360, 1));
}

TEST(MrptConvert, OffCentreScanGivesTheSamePointsInMrpt) {
  // 100 beams from -1.0 rad: centred at -0.505 rad, so the sensor yaw must carry it.
  ExpectSamePointsThroughMrpt(MakeScan(-1.0, 0.01, 100, 2));
}

TEST(MrptConvert, ScanRoundTripKeepsRangesValidityAndAngles) {
  const LaserScanEvent in = MakeScan(-M_PI, 2 * M_PI / 360, 360, 3);
  const LaserScanEvent out = mb::FromMrptScan(mb::ToMrptScan(in, 0.01), in.t_s);
  ASSERT_EQ(out.ranges_m.size(), in.ranges_m.size());
  EXPECT_NEAR(out.angle_min_rad, in.angle_min_rad, 1e-6);
  EXPECT_NEAR(out.angle_increment_rad, in.angle_increment_rad, 1e-8);
  EXPECT_DOUBLE_EQ(out.range_max_m, in.range_max_m);
  for (size_t i = 0; i < in.ranges_m.size(); ++i) {
    EXPECT_EQ(out.valid[i], in.valid[i]) << i;
    EXPECT_NEAR(out.ranges_m[i], in.ranges_m[i], 2e-6) << i;
  }
}

TEST(MrptConvert, AScanDirectionByteOtherThanZeroOrOneIsRead) {
  // MRPT copies the file's byte into the bool rightToLeft unchecked (fuzz_rawlog found 255);
  // any nonzero byte means right to left, and reading it is no undefined behaviour (UBSan).
  const LaserScanEvent in = MakeScan(-M_PI / 2, M_PI / 180, 181, 3);
  mrpt::obs::CObservation2DRangeScan scan = mb::ToMrptScan(in, 0.01);
  ASSERT_TRUE(scan.rightToLeft);
  const LaserScanEvent expected = mb::FromMrptScan(scan, in.t_s);
  const unsigned char byte = 255;
  std::memcpy(&scan.rightToLeft, &byte, 1);
  const LaserScanEvent out = mb::FromMrptScan(scan, in.t_s);
  EXPECT_EQ(out.ranges_m, expected.ranges_m);
  EXPECT_EQ(out.valid, expected.valid);
}

TEST(MrptConvert, PoseCompositionMatchesSe2IncludingWrapAtPi) {
  const SE2 cases[][2] = {{{1.0, 2.0, 3.0}, {0.3, -0.1, 0.5}},     // 3.5 rad wraps to -2.78
                          {{-1.0, 0.5, -3.1}, {0.2, 0.2, -0.3}},   // -3.4 wraps to +2.88
                          {{0.0, 0.0, M_PI - 1e-9}, {0.1, 0.0, 2e-9}}};
  for (const auto& c : cases) {
    const SE2 ours = c[0] * c[1];
    const mrpt::poses::CPose2D theirs = mb::ToMrpt(c[0]) + mb::ToMrpt(c[1]);
    EXPECT_NEAR(theirs.x(), ours.x, 1e-12);
    EXPECT_NEAR(theirs.y(), ours.y, 1e-12);
    EXPECT_NEAR(NormalizeAngle(theirs.phi() - ours.theta), 0.0, 1e-12);
    EXPECT_LE(std::abs(theirs.phi()), M_PI);
    // and the increment MRPT sees between the two poses is ours
    const SE2 between = mb::FromMrpt(mb::ToMrpt(ours) - mb::ToMrpt(c[0]));
    EXPECT_NEAR(between.x, c[1].x, 1e-12);
    EXPECT_NEAR(between.y, c[1].y, 1e-12);
    EXPECT_NEAR(NormalizeAngle(between.theta - c[1].theta), 0.0, 1e-12);
  }
}

TEST(MrptConvert, OdometryActionIsTheComposedIncrementWithThrunCovariance) {
  const std::array<double, 4> alpha = {0.05, 0.005, 0.05, 0.005};
  mb::OdometryAccumulator acc;
  const SE2 deltas[] = {{0.02, 0.0, 0.01}, {0.02, 0.001, 0.02}, {0.0, 0.0, 0.03}};
  SE2 composed;
  for (size_t i = 0; i < 3; ++i) {
    acc.Add({0.02 * (i + 1), deltas[i]}, alpha);
    composed = composed * deltas[i];
  }
  const mb::ActionNoiseFloor floor{1e-4, 2e-4};
  const auto action = mb::ToMrptAction(acc, floor);
  const auto mean = action.poseChange->getMeanVal();
  EXPECT_NEAR(mean.x(), composed.x, 1e-15);
  EXPECT_NEAR(mean.y(), composed.y, 1e-15);
  EXPECT_NEAR(mean.phi(), composed.theta, 1e-15);
  EXPECT_EQ(action.motionModelConfiguration.modelSelection, mrpt::obs::CActionRobotMovement2D::mmGaussian);

  // One step: covariance = J M Jᵀ + floor, J = d Compose / d(rot1, trans, rot2) by central differences.
  mb::OdometryAccumulator one;
  const SE2 delta(0.3, 0.1, 0.4);
  one.Add({0.02, delta}, alpha);
  const OdometryIncrement u = Decompose(delta);
  Eigen::Matrix3d J;
  for (int k = 0; k < 3; ++k) {
    const double h = 1e-6;
    OdometryIncrement up = u, um = u;
    (k == 0 ? up.rot1 : k == 1 ? up.trans : up.rot2) += h;
    (k == 0 ? um.rot1 : k == 1 ? um.trans : um.rot2) -= h;
    J.col(k) = (Compose(up).vector() - Compose(um).vector()) / (2 * h);
  }
  Eigen::Matrix3d expected = J * IncrementCovariance(u, alpha) * J.transpose();
  expected.diagonal() += Eigen::Vector3d(1e-8, 1e-8, 4e-8);
  const auto cov = action.poseChange->getCovariance();
  const auto cov1 = mb::ToMrptAction(one, floor).poseChange->getCovariance();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(cov1(r, c), expected(r, c), 1e-9) << r << "," << c;
  EXPECT_GT(cov(0, 0), 0.0);
}

TEST(MrptConvert, MrptThrunModelAlphasAreScaledSquareRootsOfOurs) {
  mrpt::obs::CActionRobotMovement2D action;
  mb::UseMrptThrunModel(action, {0.04, 0.01, 0.09, 0.16}, 2.0);
  const auto& m = action.motionModelConfiguration;
  EXPECT_EQ(m.modelSelection, mrpt::obs::CActionRobotMovement2D::mmThrun);
  EXPECT_FLOAT_EQ(m.thrunModel.alfa1_rot_rot, 0.4f);
  EXPECT_FLOAT_EQ(m.thrunModel.alfa2_rot_trans, 0.2f);
  EXPECT_FLOAT_EQ(m.thrunModel.alfa3_trans_trans, 0.6f);
  EXPECT_FLOAT_EQ(m.thrunModel.alfa4_trans_rot, 0.8f);
}

TEST(MrptConvert, BearingRangeSignConventionThroughMrptEkf) {
  // MRPT's EKF starts at the origin; its first landmark lands where our convention puts it:
  // positive bearing = counter-clockwise = +y for a robot facing +x.
  LandmarkSensorConfig cfg;
  LandmarkEvent ev{0.1, {{2.0, 0.5, 7}, {3.0, -2.0, 9}}};
  const auto obs = mb::ToMrptBearingRange(ev, cfg);
  ASSERT_EQ(obs.sensedData.size(), 2u);
  EXPECT_EQ(obs.sensedData[0].landmarkID, 7);
  EXPECT_NEAR(obs.sensor_std_yaw, cfg.sigma_bearing_deg * M_PI / 180.0, 1e-7);
  mrpt::slam::CRangeBearingKFSLAM2D ekf;
  ekf.setMinLoggingLevel(mrpt::system::LVL_ERROR);
  auto actions = std::make_shared<mrpt::obs::CActionCollection>();
  auto frame = std::make_shared<mrpt::obs::CSensoryFrame>();
  frame->insert(std::make_shared<mrpt::obs::CObservationBearingRange>(obs));
  ekf.processActionObservation(actions, frame);
  mrpt::poses::CPosePDFGaussian pose;
  std::vector<mrpt::math::TPoint2D> lms;
  std::map<unsigned int, mrpt::maps::CLandmark::TLandmarkID> ids;
  mrpt::math::CVectorDouble x;
  mrpt::math::CMatrixDouble P;
  ekf.getCurrentState(pose, lms, ids, x, P);
  ASSERT_EQ(lms.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const auto& o = ev.observations[ids.at(static_cast<unsigned>(i)) == 7 ? 0 : 1];
    EXPECT_NEAR(lms[i].x, o.range_m * std::cos(o.bearing_rad), 1e-5);
    EXPECT_NEAR(lms[i].y, o.range_m * std::sin(o.bearing_rad), 1e-5);
  }
}

TEST(MrptConvert, CovarianceToWorldRotatesPositionBlock) {
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  c(0, 0) = 4.0;  // along the start frame's x
  c(1, 1) = 1.0;
  c(2, 2) = 0.1;
  const Eigen::Matrix3d w = mb::CovarianceToWorld(SE2(1, 2, M_PI / 2), c);
  EXPECT_NEAR(w(0, 0), 1.0, 1e-12);  // start x is world y
  EXPECT_NEAR(w(1, 1), 4.0, 1e-12);
  EXPECT_NEAR(w(2, 2), 0.1, 1e-12);
}

TEST(MrptConvert, MrptGaussianModelStdsAreLinearInTheMotion) {
  // A straight 1 m step: σ_xy = floor + scale·√a3·1 m, σ_φ = floor + scale·√a2·1 m.
  mrpt::obs::CActionRobotMovement2D action;
  const mb::ActionNoiseFloor floor{0.001, 0.002};
  mb::UseMrptGaussianModel(action, {0.04, 0.01, 0.09, 0.16}, 2.0, floor);
  action.computeFromOdometry(mrpt::poses::CPose2D(1.0, 0.0, 0.0), action.motionModelConfiguration);
  const auto* g = dynamic_cast<const mrpt::poses::CPosePDFGaussian*>(action.poseChange.get());
  ASSERT_NE(g, nullptr);
  EXPECT_NEAR(std::sqrt(g->cov(0, 0)), 0.001 + 2.0 * 0.3, 1e-9);
  EXPECT_GT(std::sqrt(g->cov(1, 1)), 0.601);  // plus MRPT's heading lever arm
  EXPECT_NEAR(std::sqrt(g->cov(2, 2)), 0.002 + 2.0 * 0.1, 1e-9);
  // Draws (what each RBPF particle gets) scatter with that std, not all the same value.
  mb::SeedMrptRandom(3);
  mrpt::poses::CPoseRandomSampler sampler;
  sampler.setPosePDF(*action.poseChange);
  double sum = 0, sum2 = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    mrpt::poses::CPose2D p;
    sampler.drawSample(p);
    sum += p.x();
    sum2 += p.x() * p.x();
  }
  const double std_x = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  EXPECT_NEAR(std_x, 0.601, 0.05);
}

TEST(MrptConvert, UpsampledGridScanGivesTheSamePointsInMrpt) {
  ExpectSamePointsThroughMrpt(MakeScan(-M_PI, 2 * M_PI / 360, 360, 4), 16);
  ExpectSamePointsThroughMrpt(MakeScan(-1.0, 0.01, 100, 5), 3);
}

TEST(MrptConvert, GridInsertionAndLikelihoodFieldAgreeOnHeading) {
  // MRPT inserts beam i into a grid at yaw - aperture/2 + i·aperture/N but scores points at
  // yaw - aperture/2 + i·aperture/(N-1). A grid built from one scan must score that same
  // scan best at the pose it was inserted from, not half a beam step (0.5°) off.
  std::mt19937_64 rng(6);
  const LaserScanEvent scan = testing::RayCastScan(testing::RoomWalls(), SE2(1.013, 0.527, 0.3), 360, 0.0, rng);
  auto obs = std::make_shared<mrpt::obs::CObservation2DRangeScan>(mb::ToMrptScanForGrid(scan, 0.01, 16));
  mrpt::maps::CPointsMap::TInsertionOptions points;
  points.minDistBetweenLaserPoints = 0.0f;
  obs->buildAuxPointsMap<mrpt::maps::CPointsMap>(&points);
  mrpt::maps::COccupancyGridMap2D grid(-10.0f, 10.0f, -10.0f, 10.0f, 0.05f);
  grid.insertionOptions.decimation = 16;
  grid.likelihoodOptions.likelihoodMethod = mrpt::maps::COccupancyGridMap2D::lmLikelihoodField_Thrun;
  grid.likelihoodOptions.LF_stdHit = 0.05f;
  grid.likelihoodOptions.LF_decimation = 1;
  grid.insertObservation(*obs);
  auto loglik = [&](double yaw_deg) {
    return grid.computeObservationLikelihood(*obs, mrpt::poses::CPose3D(0, 0, 0, yaw_deg * M_PI / 180, 0, 0));
  };
  EXPECT_GT(loglik(0.0), loglik(0.5));
  EXPECT_GT(loglik(0.0), loglik(-0.5));
}

}  // namespace
}  // namespace slambox
