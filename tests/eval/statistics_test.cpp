#include "eval/statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace slambox {
namespace {

TEST(Statistics, HandComputedEvenCount) {
  const ErrorStatistics s = ComputeStatistics({4.0, 1.0, 3.0, 2.0});
  EXPECT_EQ(s.count, 4);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);              // (2 + 3) / 2, as numpy.median
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));     // ddof 0: (2.25 + 0.25 + 0.25 + 2.25) / 4
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(30.0 / 4));
  EXPECT_DOUBLE_EQ(s.sse, 30.0);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
}

TEST(Statistics, HandComputedOddCountAndSingle) {
  const ErrorStatistics s = ComputeStatistics({3.0, 1.0, 2.0});
  EXPECT_DOUBLE_EQ(s.median, 2.0);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(2.0 / 3.0));
  const ErrorStatistics one = ComputeStatistics({0.7});
  EXPECT_DOUBLE_EQ(one.rmse, 0.7);
  EXPECT_DOUBLE_EQ(one.std, 0.0);
}

TEST(Statistics, ZerosGiveExactZeros) {
  const ErrorStatistics s = ComputeStatistics(std::vector<double>(10, 0.0));
  EXPECT_EQ(s.rmse, 0.0);
  EXPECT_EQ(s.mean, 0.0);
  EXPECT_EQ(s.std, 0.0);
  EXPECT_EQ(s.max, 0.0);
  EXPECT_EQ(s.sse, 0.0);
}

TEST(Statistics, EmptyIsNullInJson) {
  const ErrorStatistics s = ComputeStatistics({});
  EXPECT_EQ(s.count, 0);
  EXPECT_TRUE(std::isnan(s.rmse));
  nlohmann::json j;
  AddStatistics(j, "ate", "_m", "_m2", s);
  EXPECT_TRUE(j["ate_rmse_m"].is_null());
  EXPECT_TRUE(j["ate_sse_m2"].is_null());
  EXPECT_EQ(j.size(), 7u);
}

TEST(Statistics, PercentileMatchesNumpyLinear) {
  // numpy.percentile([1, 2, 3, 4, 5], 95) = 4.8; ([10, 20], 25) = 12.5
  EXPECT_NEAR(Percentile({5, 1, 4, 2, 3}, 95.0), 4.8, 1e-12);
  EXPECT_NEAR(Percentile({20, 10}, 25.0), 12.5, 1e-12);
  EXPECT_DOUBLE_EQ(Percentile({7}, 95.0), 7.0);
  EXPECT_DOUBLE_EQ(Percentile({1, 2, 3}, 100.0), 3.0);
  EXPECT_TRUE(std::isnan(Percentile({}, 50.0)));
}

}  // namespace
}  // namespace slambox
