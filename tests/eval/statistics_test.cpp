#include "eval/statistics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

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

TEST(Interval, ExactBootstrapOfTwoAndFiveValuesMatchesTheBinomialClosedForm) {
  // {1, 3}: resample means 1, 2, 3 with probabilities 1/4, 1/2, 1/4 -> [1, 3].
  const MeanInterval two = IntervalOfMean({3.0, 1.0}, IntervalMethod::kBootstrap, true);
  EXPECT_EQ(two.method, IntervalMethod::kBootstrap);
  EXPECT_DOUBLE_EQ(two.lo, 1.0);
  EXPECT_DOUBLE_EQ(two.hi, 3.0);
  // {0, 0, 0, 0, 10}: mean = 2k, k ~ Binomial(5, 0.2); P(k = 0) = 0.328 >= 2.5 %,
  // P(k <= 2) = 0.942 < 97.5 % <= P(k <= 3) = 0.993 -> [0, 6].
  const MeanInterval five = IntervalOfMean({0, 10, 0, 0, 0}, IntervalMethod::kAuto, true);
  EXPECT_EQ(five.method, IntervalMethod::kBootstrap);
  EXPECT_DOUBLE_EQ(five.lo, 0.0);
  EXPECT_DOUBLE_EQ(five.hi, 6.0);
  // {1, 2, 3}: P(mean = 1) = 1/27 > 2.5 %: with three seeds the interval is the range.
  const MeanInterval three = IntervalOfMean({2, 3, 1}, IntervalMethod::kAuto, true);
  EXPECT_DOUBLE_EQ(three.lo, 1.0);
  EXPECT_DOUBLE_EQ(three.hi, 3.0);
}

TEST(Interval, ResampledBootstrapMatchesTheBinomialAndIsDeterministic) {
  // Eleven zeros and one 12: mean = k ~ Binomial(12, 1/12); P(k = 0) = 0.352,
  // P(k <= 2) = 0.935 < 97.5 % < P(k <= 3) = 0.986 -> [0, 3] (20000 resamples; the
  // 97.5 % point is ~200 resamples from either boundary).
  std::vector<double> v(11, 0.0);
  v.push_back(12.0);
  const MeanInterval a = IntervalOfMean(v, IntervalMethod::kBootstrap, true);
  EXPECT_DOUBLE_EQ(a.lo, 0.0);
  EXPECT_DOUBLE_EQ(a.hi, 3.0);
  std::reverse(v.begin(), v.end());
  const MeanInterval b = IntervalOfMean(v, IntervalMethod::kBootstrap, true);
  EXPECT_EQ(a.lo, b.lo);
  EXPECT_EQ(a.hi, b.hi);
}

TEST(Interval, StudentTFromTenValuesAndNeverBelowZeroForAnError) {
  EXPECT_EQ(ResolveInterval(IntervalMethod::kAuto, 9), IntervalMethod::kBootstrap);
  EXPECT_EQ(ResolveInterval(IntervalMethod::kAuto, 10), IntervalMethod::kStudentT);
  // A skewed error of 3 seeds: the t-interval 0.31 -+ 4.303 * 0.51 / sqrt(3) goes below 0.
  const std::vector<double> skewed{0.01, 0.02, 0.9};
  const SampleSummary s = Summarize(skewed);
  const MeanInterval t = IntervalOfMean(skewed, IntervalMethod::kStudentT, false);
  EXPECT_NEAR(t.lo, s.mean - 4.303 * s.std / std::sqrt(3.0), 1e-12);
  EXPECT_LT(t.lo, 0.0);
  const MeanInterval clipped = IntervalOfMean(skewed, IntervalMethod::kStudentT, true);
  EXPECT_EQ(clipped.lo, 0.0);
  EXPECT_TRUE(clipped.clipped);
  EXPECT_NEAR(clipped.hi, t.hi, 1e-15);
  const MeanInterval boot = IntervalOfMean(skewed, IntervalMethod::kAuto, true);
  EXPECT_DOUBLE_EQ(boot.lo, 0.01);
  EXPECT_DOUBLE_EQ(boot.hi, 0.9);
  EXPECT_EQ(IntervalOfMean({}, IntervalMethod::kAuto, true).n, 0);
  EXPECT_DOUBLE_EQ(IntervalOfMean({0.5}, IntervalMethod::kAuto, true).hi, 0.5);
}

}  // namespace
}  // namespace slambox
