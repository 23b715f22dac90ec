#include "slam/detection_rate.hpp"

#include <gtest/gtest.h>

namespace slambox {
namespace {

TEST(DetectionRate, LaplaceRuleWithTheConfiguredProbabilityAsPrior) {
  DetectionRate r = MakeDetectionRate(40.0, 4, 0.9);  // bands [0,10) [10,20) [20,30) [30,40)
  EXPECT_DOUBLE_EQ(DetectionProbability(r, 5.0), 0.9);  // no data: the prior
  for (int k = 0; k < 3; ++k) CountExpected(r, 12.0, k == 0);  // seen 1 of 3 in band 1
  EXPECT_DOUBLE_EQ(DetectionProbability(r, 19.9), (1.0 + 0.9) / (3.0 + 1.0));
  EXPECT_DOUBLE_EQ(DetectionProbability(r, 10.0), (1.0 + 0.9) / 4.0);
  EXPECT_DOUBLE_EQ(DetectionProbability(r, 9.99), 0.9);  // band 0 untouched
  // Ranges at or beyond range_max (and negative) fall in the end bands.
  CountExpected(r, 55.0, true);
  EXPECT_DOUBLE_EQ(DetectionProbability(r, 39.0), (1.0 + 0.9) / 2.0);
  CountExpected(r, -1.0, false);
  EXPECT_DOUBLE_EQ(DetectionProbability(r, 0.0), 0.9 / 2.0);
}

TEST(DetectionRate, ConvergesToTheFrequency) {
  DetectionRate r = MakeDetectionRate(10.0, 1, 1.0);
  for (int k = 0; k < 1000; ++k) CountExpected(r, 3.0, k % 4 == 0);  // 250 of 1000
  EXPECT_NEAR(DetectionProbability(r, 3.0), 0.25, 1e-3);
}

}  // namespace
}  // namespace slambox
