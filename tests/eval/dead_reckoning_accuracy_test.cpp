// Accuracy and consistency of the evaluator on a synthetic run: dead reckoning over a
// seeded synthetic stream with the motion model's covariance propagation
// (P' = G P G^T + V M V^T, Thrun Table 5.6). The test's estimator linearizes at the true
// increments, where the stream's noise was drawn, so its covariance is the true one (to
// first order): ANEES over Monte Carlo runs stays in the chi-square band, and a 10x
// overconfident covariance is caught. (Linearizing at the noisy increment would inflate
// the covariance during turns in place, where Thrun's rot1 is ill-defined.)
#include <gtest/gtest.h>

#include <variant>

#include "core/odometry_model.hpp"
#include "eval/consistency.hpp"
#include "eval/evaluate.hpp"
#include "tests/support/synthetic_stream.hpp"

namespace slambox {
namespace {

Stream MakeStream(std::uint64_t seed) {
  testing::SyntheticOptions o;
  o.seed = seed;
  o.sensors.odometry = OdometryConfig{};
  o.sensors.odometry->alpha = {0.01, 0.001, 0.01, 0.001};
  return testing::MakeSyntheticStream(o, World{});
}

Estimate DeadReckon(const Stream& s, double covariance_scale) {
  Estimate e;
  PoseEstimate p{0.0, s.header.start_pose, Eigen::Matrix3d::Zero(), true};
  p.covariance.diagonal().setConstant(1e-12);  // a tiny prior keeps P invertible at t = 0
  e.trajectory.push_back(p);
  size_t step = 0;
  for (const auto& ev : s.events) {
    const auto* odo = std::get_if<OdometryEvent>(&ev);
    if (!odo) continue;
    ++step;  // odometry event k follows ground-truth pose k - 1 and lands on pose k
    const OdometryIncrement u_true = Decompose(Between(s.groundtruth[step - 1].pose, s.groundtruth[step].pose));
    const MotionPrediction m = PredictMotion(p.pose, u_true);
    const Eigen::Matrix3d M = IncrementCovariance(u_true, s.header.sensors.odometry->alpha) * covariance_scale;
    p.covariance = m.J_pose_pose * p.covariance * m.J_pose_pose.transpose() +
                   m.J_pose_increment * M * m.J_pose_increment.transpose();
    p.pose = p.pose * odo->delta;
    p.t_s = odo->t_s;
    e.trajectory.push_back(p);
  }
  return e;
}

TEST(DeadReckoningAccuracy, ConsistentCovarianceStaysInTheAneesBand) {
  const int runs = 30;
  std::vector<std::vector<double>> nees, nees_over;
  double ate_sum = 0.0;
  for (int seed = 0; seed < runs; ++seed) {
    const Stream s = MakeStream(seed + 1);
    const GroundTruth gt{s.groundtruth, World{}};
    const Evaluation ok = EvaluateEstimate(gt, DeadReckon(s, 1.0));
    const Evaluation over = EvaluateEstimate(gt, DeadReckon(s, 0.01));
    ASSERT_EQ(ok.metrics.status, RunStatus::kOk);
    ate_sum += ok.metrics.ate.rmse;
    std::vector<double> a, b;
    for (size_t k = 1; k < ok.series.nees.size(); k += 10) {  // skip the prior-only first step
      a.push_back(ok.series.nees[k]);
      b.push_back(over.series.nees[k]);
    }
    nees.push_back(a);
    nees_over.push_back(b);
  }
  const AneesResult r = AneesOverRuns(nees, 3);
  const AneesResult r_over = AneesOverRuns(nees_over, 3);
  double mean = 0.0;
  for (double v : r.anees) mean += v / r.anees.size();
  std::printf("ANEES mean %.3f, fraction in [%.3f, %.3f]: %.3f; overconfident: %.3f; mean ATE rmse %.3f m\n", mean,
              r.band.lo, r.band.hi, r.fraction_inside, r_over.fraction_inside, ate_sum / runs);
  EXPECT_GT(r.fraction_inside, 0.8);
  EXPECT_NEAR(mean, 3.0, 0.6);
  EXPECT_LT(r_over.fraction_inside, 0.1);
  EXPECT_GT(ate_sum / runs, 0.01);  // the noise is real: the estimate is not the truth
}

TEST(DeadReckoningAccuracy, SameSeedGivesBitIdenticalMetrics) {
  const Stream s = MakeStream(5);
  const GroundTruth gt{s.groundtruth, World{}};
  const std::string a = ToJson(EvaluateEstimate(gt, DeadReckon(s, 1.0)).metrics).dump();
  const std::string b = ToJson(EvaluateEstimate(gt, DeadReckon(MakeStream(5), 1.0)).metrics).dump();
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace slambox
