// mrpt-ekf-slam on a landmark loop: deterministic, better than dead reckoning, landmarks
// with their true ids near the truth.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "slam/mrpt/mrpt_ekf_slam.hpp"
#include "tests/mrpt/mrpt_test_support.hpp"

namespace slambox::testing {
namespace {

Estimate RunEkf(const Stream& s, const ParamOverrides& overrides = {}) {
  auto module = MrptEkfSlamModule().create(overrides);
  return Replay(*module, s);
}

TEST(MrptEkfSlam, DeterministicForAStream) {
  const Stream s = LandmarkStream(3, true);
  ExpectIdenticalTrajectories(RunEkf(s), RunEkf(s));
}

TEST(MrptEkfSlam, BeatsDeadReckoningOnALandmarkLoopWithKnownIds) {
  const Stream s = LandmarkStream(3, true);
  const Estimate e = RunEkf(s);
  ASSERT_GT(e.trajectory.size(), 2000u);  // a pose at every odometry event
  const double rmse = Rmse(PositionErrors(e, s));
  const double dr = DeadReckoningRmse(e, s);
  EXPECT_LT(rmse, 0.5 * dr) << "ekf " << rmse << " dead reckoning " << dr;
  EXPECT_LT(rmse, 0.15);
  ASSERT_EQ(e.landmarks.size(), s.header.world.landmarks.size());
  for (const auto& lm : e.landmarks) {
    ASSERT_GE(lm.id, 0);
    ASSERT_LT(lm.id, static_cast<int>(s.header.world.landmarks.size()));
    const Eigen::Vector2d truth = s.header.world.landmarks[lm.id].position;
    EXPECT_LT((lm.position - truth).norm(), 0.25) << "landmark " << lm.id;
    EXPECT_TRUE(lm.has_covariance);
    EXPECT_GT(lm.covariance.determinant(), 0.0);
  }
  for (const auto& p : e.trajectory) {
    ASSERT_TRUE(p.has_covariance);
    ASSERT_GE(p.covariance.diagonal().minCoeff(), 0.0);
  }
}

TEST(MrptEkfSlam, UnknownIdsUseMrptDataAssociation) {
  const Stream s = LandmarkStream(4, false);
  const Estimate e = RunEkf(s);
  const double rmse = Rmse(PositionErrors(e, s));
  EXPECT_LT(rmse, DeadReckoningRmse(e, s));
  EXPECT_LT(rmse, 0.3);
  EXPECT_GE(e.landmarks.size(), s.header.world.landmarks.size());
}

TEST(MrptEkfSlam, BadParameterIsAnInputError) {
  EXPECT_THROW(MrptEkfSlamModule().create({{"data_association", "magic"}}), InputError);
}

}  // namespace
}  // namespace slambox::testing
