// AssembleLandmarkLog's refusals (datasets/landmark_log.hpp): what no reader can catch
// because it comes from options or from the caller's ids. Its events are checked through
// its users (tests/datasets/victoria_park_test.cpp, tests/app/graph_log_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "datasets/landmark_log.hpp"

namespace slambox {
namespace {

LandmarkLog OneStep() {
  LandmarkLog log;
  log.increments = {SE2(1, 0, 0)};
  log.increment_covariances = {Eigen::Matrix3d::Identity() * 0.01};
  log.sightings = {{.pose = 1, .landmark = 3, .point = {2, 0}, .covariance = Eigen::Matrix2d::Identity() * 0.01}};
  return log;
}

std::string Refusal(const LandmarkLog& log, const LandmarkLogOptions& options) {
  try {
    AssembleLandmarkLog(log, "log.txt", options);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "log.txt");
    return e.what();
  }
  return "accepted";
}

TEST(LandmarkLog, RefusesPeriodsAndIdsAStreamCannotHold) {
  EXPECT_NO_THROW(AssembleLandmarkLog(OneStep(), "log.txt", {.pose_period_s = 1.0}));
  for (const double period : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity(), 1e300})
    EXPECT_NE(Refusal(OneStep(), {.pose_period_s = period}).find("--pose-period-s"), std::string::npos) << period;
  EXPECT_NE(Refusal(OneStep(), {.fov_deg = 400}).find("--fov-deg"), std::string::npos);
  LandmarkLog negative = OneStep();
  negative.sightings[0].landmark = -1;
  EXPECT_NE(Refusal(negative, {}).find("landmark id -1"), std::string::npos);
  LandmarkLog outside = OneStep();
  outside.sightings[0].pose = 2;
  EXPECT_NE(Refusal(outside, {}).find("outside the chain"), std::string::npos);
  LandmarkLog short_truth = OneStep();
  short_truth.true_poses = {SE2()};
  EXPECT_NE(Refusal(short_truth, {}).find("ground truth for 1 poses"), std::string::npos);
}

TEST(LandmarkLog, IsAConvertedLogEvenWithGroundTruth) {
  LandmarkLog with_truth = OneStep();
  with_truth.true_poses = {SE2(), SE2(1, 0, 0)};
  EXPECT_TRUE(IsConvertedLog(AssembleLandmarkLog(OneStep(), "log.txt", {}).header));
  EXPECT_TRUE(IsConvertedLog(AssembleLandmarkLog(with_truth, "log.txt", {}).header));
  StreamHeader simulated;
  simulated.scenario_yaml = "version: 1\nname: loop\n";
  EXPECT_FALSE(IsConvertedLog(simulated));
}

}  // namespace
}  // namespace slambox
