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
  EXPECT_TRUE(NumberOrNull(s.rmse).is_null());
  EXPECT_TRUE(NumberOrNull(INFINITY).is_null());
  EXPECT_EQ(NumberOrNull(0.5), nlohmann::json(0.5));
}

TEST(SampleSummary, SweepCellStatisticsMatchHandComputedValues) {
  const SampleSummary s = Summarize({2.0, 4.0, 4.0, 5.0, NAN});
  EXPECT_EQ(s.n, 4);
  EXPECT_DOUBLE_EQ(s.mean, 3.75);
  EXPECT_NEAR(s.std, std::sqrt(4.75 / 3.0), 1e-12);  // squares 3.0625+0.0625+0.0625+1.5625, n-1 = 3
  EXPECT_DOUBLE_EQ(s.median, 4.0);
  EXPECT_NEAR(s.ci95_half, 3.182 * s.std / 2.0, 1e-12);  // t(0.975, 3) = 3.182
  EXPECT_EQ(Summarize({}).n, 0);
  EXPECT_EQ(Summarize({7.0}).std, 0.0);
  EXPECT_EQ(Summarize({7.0}).ci95_half, 0.0);
}

TEST(SampleSummary, QuartilesWhiskersAndInterval) {
  // 1..9 and an outlier 100: type-7 quartiles of 10 values.
  const SampleSummary s = Summarize({5, 1, 9, 2, 8, 3, 7, 4, 6, 100, NAN});
  EXPECT_EQ(s.n, 10);
  EXPECT_DOUBLE_EQ(s.median, 5.5);
  EXPECT_DOUBLE_EQ(s.q1, 3.25);
  EXPECT_DOUBLE_EQ(s.q3, 7.75);
  EXPECT_DOUBLE_EQ(s.whisker_lo, 1.0);
  EXPECT_DOUBLE_EQ(s.whisker_hi, 9.0);
  ASSERT_EQ(s.outliers, std::vector<double>{100.0});
  // Mean 14.5, sample sd 30.15239 (by hand: sqrt(8182.5 / 9)), t_{0.975,9} = 2.262.
  EXPECT_DOUBLE_EQ(s.mean, 14.5);
  EXPECT_NEAR(s.ci95_half, 2.262 * 30.15239 / std::sqrt(10.0), 1e-3);
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
