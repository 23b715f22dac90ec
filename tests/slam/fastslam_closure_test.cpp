// A FastSLAM particle's loop closure by re-observation and its path relaxation
// (slam/fastslam_closure.hpp): the drift prior's closed form, the step errors' consistency with
// the robot's correction, the motion of points along the path, and a scripted closure on a
// circular lap whose end drifted.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <vector>

#include "slam/fastslam_closure.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {
namespace {

Eigen::Vector3d StepJacobian(const Eigen::Vector2d& robot, const Eigen::Vector2d& step) {
  return {-(robot.y() - step.y()), robot.x() - step.x(), 1.0};
}

std::vector<DriftStep> ThreeSteps() {
  return {{{0.0, 0.0}, 1e-4, 4e-4, 1e-4}, {{10.0, 0.0}, 2e-4, 1e-4, 3e-4}, {{10.0, 10.0}, 3e-4, 2e-4, 6e-4}};
}

TEST(PathRelaxation, DriftCovarianceIsTheSumOverStepsOfTheirTurnsAndShifts) {
  const std::vector<DriftStep> steps = ThreeSteps();
  const Eigen::Vector2d robot(0.0, 10.0);
  Eigen::Matrix3d expected = Eigen::Matrix3d::Zero();
  for (const DriftStep& k : steps) {
    const Eigen::Vector3d J = StepJacobian(robot, k.xy);
    expected += k.heading_rad2 * J * J.transpose();
    expected.topLeftCorner<2, 2>() += k.translation_m2 * Eigen::Matrix2d::Identity();
  }
  EXPECT_LT((PathDriftCovariance(steps, robot) - expected).norm(), 1e-15);
  // By hand for the first step alone: J = (-10, 0, 1).
  const Eigen::Matrix3d one = PathDriftCovariance(std::span(steps).first(1), robot);
  EXPECT_DOUBLE_EQ(one(0, 0), 1e-4 * 100 + 4e-4);
  EXPECT_DOUBLE_EQ(one(1, 1), 4e-4);
  EXPECT_DOUBLE_EQ(one(0, 2), -1e-4 * 10);
  EXPECT_DOUBLE_EQ(one(2, 2), 1e-4);
}

TEST(PathRelaxation, TheStepErrorsAddUpToTheRobotsCorrection) {
  const std::vector<DriftStep> steps = ThreeSteps();
  const Eigen::Vector2d robot(0.0, 10.0);
  const Eigen::Matrix3d C = PathDriftCovariance(steps, robot);
  const Eigen::Vector3d dx(1e-5, -2e-5, 3e-6);  // small: Move is the linear model to first order
  const PathCorrection c = RelaxPath(steps, robot, C.ldlt().solve(dx));
  // The heading turns by exactly dx_theta; the robot's position, seen after the last step,
  // moves by dx_xy (up to second order in the angle).
  EXPECT_NEAR(c.Turn(1.0), dx.z(), 1e-18);
  EXPECT_LT((c.Move(robot, 1.0) - robot - dx.head<2>()).norm(), 1e-10);
  // Nothing before the first step's end moves; a point seen by the first step turns by its error only.
  EXPECT_EQ(c.Move(Eigen::Vector2d(3.0, 4.0), 0.5e-4), Eigen::Vector2d(3.0, 4.0));
  EXPECT_EQ(c.Turn(0.5e-4), 0.0);
  const Eigen::Vector3d lambda = C.ldlt().solve(dx);
  EXPECT_NEAR(c.Turn(1e-4), 1e-4 * StepJacobian(robot, steps[0].xy).dot(lambda), 1e-18);
}

TEST(PathRelaxation, APointMovesByARotationAboutTheStepsWeightedCentreAndAShift) {
  // One step at (2, 0): its error turns every later point about (2, 0) and shifts it by D.
  const std::vector<DriftStep> step = {{{2.0, 0.0}, 1e-2, 1e-2, 1e-2}};
  const Eigen::Vector2d robot(2.0, 5.0);
  const Eigen::Vector3d dx(0.3, 0.2, 0.5);
  const PathCorrection c = RelaxPath(step, robot, PathDriftCovariance(step, robot).ldlt().solve(dx));
  const double a = c.Turn(1.0);
  const Eigen::Vector2d m(7.0, -1.0);
  const Eigen::Vector2d expected = RotationMatrix(a) * (m - Eigen::Vector2d(2.0, 0.0)) + Eigen::Vector2d(2.0, 0.0) + c.D[0];
  EXPECT_LT((c.Move(m, 1.0) - expected).norm(), 1e-12);
}

// A lap on a circle of radius 20 m about (0, 20), 100 steps, dead reckoned with a heading
// error of 0.8 mrad per step (the drift model's kind): its end believes it is about 3 m and
// 4.6 degrees from the start it is back at. Two landmarks mapped at the start come back.
const Eigen::Vector2d kOldA(5.0, -3.0), kOldB(-4.0, 6.0), kBefore(0.0, -8.0);

struct Lap {
  FastSlamParticle particle;
  std::vector<DriftSample> drift;
  ParticleUpdateOptions settings;
  std::vector<int> keys;
  std::vector<Eigen::Vector2d> z;
};

// Fills `lap` in place: its settings hold a span of its own drift samples.
void MakeLap(Lap& lap) {
  FastSlamParticle& p = lap.particle;
  SE2 believed, truth;
  for (int k = 0; k <= 100; ++k) {
    if (k > 0) {
      const double phi = 2.0 * M_PI * k / 100.0;
      const SE2 next(20.0 * std::sin(phi), 20.0 - 20.0 * std::cos(phi), phi);
      believed = believed * (truth.inverse() * next) * SE2(0.0, 0.0, 8e-4);
      truth = next;
    }
    p.path = ExtendPath(p.path, k, believed);
    lap.drift.push_back({static_cast<double>(k), 1e-4 * (k + 1), 1e-6 * (k + 1)});
  }
  p.pose = p.path->pose;
  const auto landmark = [](const Eigen::Vector2d& xy, double seen_rad2) {
    LandmarkGaussian lm;
    lm.mean = xy;
    lm.covariance = 1e-4 * Eigen::Matrix2d::Identity();
    lm.seen_heading_variance_rad2 = seen_rad2;
    return lm;
  };
  SetLandmark(p.map, 0, landmark(kOldA, 2e-4));
  SetLandmark(p.map, 1, landmark(kOldB, 2e-4));
  SetLandmark(p.map, 2, landmark(kBefore, 1e-4));  // seen before them: stays
  SetLandmark(p.map, 3, landmark(p.pose * Eigen::Vector2d(6.0, 1.0), 1e-4 * 101));  // seen at the end
  lap.settings.travel_m = 125.0;
  lap.settings.heading_variance_rad2 = 1e-4 * 101;
  lap.settings.closure_old_after_m = 96.0;
  lap.settings.range_max_m = 12.0;
  lap.settings.closure_gate_prob = 0.99;
  lap.settings.R = Eigen::Vector2d(1e-4, 1e-6).asDiagonal();
  lap.settings.drift = lap.drift;
  lap.keys = {0, 1};
  lap.z = {PredictObservation(SE2(), kOldA).z, PredictObservation(SE2(), kOldB).z};
}

TEST(FastSlamClosure, ADriftedReturnMovesThePoseAndTheLapsMap) {
  Lap lap;
  MakeLap(lap);
  const Eigen::Vector2d seen_at_end = lap.particle.pose.inverse() * FindLandmark(lap.particle.map, 3)->mean;
  ASSERT_TRUE(CorrectClosure(lap.particle, lap.keys, lap.z, lap.settings).has_value());
  const SE2& pose = lap.particle.pose;
  EXPECT_NEAR(pose.x, 0.0, 0.01);  // the two old landmarks fix all three dof
  EXPECT_NEAR(pose.y, 0.0, 0.01);
  EXPECT_NEAR(pose.theta, 0.0, 0.002);
  EXPECT_EQ(FindLandmark(lap.particle.map, 0)->mean, kOldA);  // the old ones and those before stay
  EXPECT_EQ(FindLandmark(lap.particle.map, 2)->mean, kBefore);
  // The landmark seen at the end keeps its place relative to the robot (second order in the drift).
  EXPECT_LT((pose.inverse() * FindLandmark(lap.particle.map, 3)->mean - seen_at_end).norm(), 0.1);
  // The path follows at output: its end is the corrected pose, its start did not move.
  const std::vector<PoseEstimate> path = RelaxedPath(lap.particle.path, lap.particle.relaxations.get(), lap.drift);
  ASSERT_EQ(path.size(), 101u);
  EXPECT_EQ(path.front().pose.translation(), Eigen::Vector2d(0.0, 0.0));
  EXPECT_LT((path.back().pose.translation() - pose.translation()).norm(), 0.1);
  EXPECT_NEAR(path.back().pose.theta, pose.theta, 1e-3);
  // Halfway the believed path is 0.93 m off; relaxed, 0.054 m (the drift is the model's kind).
  const SE2 truth_half(0.0, 40.0, M_PI);
  const double before = (PathPoses(lap.particle.path)[50]->pose.translation() - truth_half.translation()).norm();
  EXPECT_GT(before, 0.5);
  EXPECT_LT((path[50].pose.translation() - truth_half.translation()).norm(), 0.1 * before);
}

TEST(FastSlamClosure, OnlyTheStretchSinceThePathLastSawItsOldMapRelaxes) {
  // The particle re-observed old landmarks halfway (heading variance 5e-3, travel 20 m, more
  // than the window before now): the loop closed then, so the half before stays.
  Lap lap;
  MakeLap(lap);
  lap.particle.old_seen_travel_m = 20.0;
  lap.particle.old_seen_heading_rad2 = 5e-3;
  LandmarkGaussian early = *FindLandmark(lap.particle.map, 3);
  early.seen_heading_variance_rad2 = 3e-3;  // seen before the anchor
  SetLandmark(lap.particle.map, 4, early);
  ASSERT_TRUE(CorrectClosure(lap.particle, lap.keys, lap.z, lap.settings).has_value());
  EXPECT_EQ(lap.particle.closure_since_rad2, 5e-3);
  EXPECT_EQ(FindLandmark(lap.particle.map, 4)->mean, early.mean);
  const std::vector<PoseEstimate> path = RelaxedPath(lap.particle.path, lap.particle.relaxations.get(), lap.drift);
  const std::vector<const PathNode*> raw = PathPoses(lap.particle.path);
  EXPECT_EQ(path[30].pose.translation(), raw[30]->pose.translation());  // before the anchor
  EXPECT_GT((path[80].pose.translation() - raw[80]->pose.translation()).norm(), 0.5);
}

TEST(FastSlamClosure, ACorrectionTheDriftMakesUnlikelyIsNotSpread) {
  // The lap's steps under its own drift prior C: a 10 m shift without a turn is dx^T C^-1 dx
  // far beyond the 3-dof gate (it would be spread as turns of opposite signs along the path).
  Lap lap;
  MakeLap(lap);
  const std::vector<DriftStep> steps = PathSince(lap.particle.path.get(), 2e-4, lap.drift);
  ASSERT_EQ(steps.size(), 100u);  // the steps since the old sightings, the first one's end at 2e-4
  const Eigen::Matrix3d C = PathDriftCovariance(steps, lap.particle.pose.translation());
  const SE2 before = lap.particle.pose;
  const SE2 shifted = SE2(10.0, 0.0, 0.0) * before;
  const Eigen::Vector3d dx(10.0, 0.0, 0.0);
  ASSERT_GT(dx.dot(C.ldlt().solve(dx)), 11.35);  // chi2_3(0.99)
  EXPECT_FALSE(RelaxParticle(lap.particle, shifted, steps, C, 11.35, 2e-4, [](int) { return false; }));
  EXPECT_EQ(lap.particle.pose.translation(), before.translation());
  EXPECT_EQ(lap.particle.relaxations, nullptr);
  // A small one within the gate is spread, and recorded for the path.
  const SE2 nudged = SE2(0.1, 0.0, 0.0) * before;
  EXPECT_TRUE(RelaxParticle(lap.particle, nudged, steps, C, 11.35, 2e-4, [](int) { return false; }));
  EXPECT_EQ(lap.particle.pose.translation(), nudged.translation());
  EXPECT_NE(lap.particle.relaxations, nullptr);
}

TEST(FastSlamClosure, NoClosureWhereThePriorExplainsTheReturnOrNoStretchWithoutOldLandmarksPreceded) {
  Lap lap;
  MakeLap(lap);
  lap.particle.pose = SE2();  // at the truth: the innovation passes the gate
  EXPECT_FALSE(CorrectClosure(lap.particle, lap.keys, lap.z, lap.settings).has_value());
  Lap again;
  MakeLap(again);
  again.particle.old_seen_travel_m = 100.0;  // old landmarks seen 25 m ago: the loop was closed before
  EXPECT_FALSE(CorrectClosure(again.particle, again.keys, again.z, again.settings).has_value());
  Lap young;
  MakeLap(young);
  young.settings.travel_m = 90.0;  // within the widest window: nothing is old
  EXPECT_FALSE(CorrectClosure(young.particle, young.keys, young.z, young.settings).has_value());
}

}  // namespace
}  // namespace slambox
