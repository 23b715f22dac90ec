#include "slam/growth_replay.hpp"

#include <Eigen/Cholesky>
#include <stdexcept>

#include "slam/keyframe_decimation.hpp"
#include "slam/pose_graph.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

SE2 ComposedMotion(const SE2& solved_previous, const SE2& frontend_previous, const SE2& frontend_now,
                   const OdometryConstraint& odometry, double jump_gate_chi2) {
  const SE2 motion = frontend_previous.inverse() * frontend_now;
  if (jump_gate_chi2 > 0) {
    const Eigen::Vector3d e = EdgeError(SE2(), motion, odometry.T_from_to);  // (motion vs odometry), angle wrapped
    // Weighed as the solve weighs the factor (floored: a robot at rest has a zero covariance).
    if (e.dot(FactorCovariance(odometry).ldlt().solve(e)) > jump_gate_chi2) return solved_previous * odometry.T_from_to;
  }
  return solved_previous * motion;
}

bool GrowingGraphSolveDue(int keyframe, int last_solve_keyframe, int solve_every_keyframes, int max_keyframes) {
  return keyframe - last_solve_keyframe >= solve_every_keyframes * DecimationStride(keyframe, max_keyframes);
}

namespace {

// Solves the keyframes 0..last of `full` from the guesses in `g` (poses 0..last valid;
// landmarks not yet in g.landmarks start at their first observation) and writes the
// solution back into `g`.
void SolveUpTo(const LandmarkGraph& full, int last, const GrowthReplaySettings& settings, LandmarkGraph& g) {
  LandmarkGraph sub;
  sub.observation_covariance = full.observation_covariance;
  sub.poses.assign(g.poses.begin(), g.poses.begin() + last + 1);
  sub.odometry.assign(full.odometry.begin(), full.odometry.begin() + last);
  for (const RangeBearingConstraint& o : full.observations) {
    if (o.keyframe > last || !full.landmarks.count(o.landmark)) continue;
    sub.observations.push_back(o);
    if (!g.landmarks.count(o.landmark))
      g.landmarks[o.landmark] = InverseObservation(sub.poses[static_cast<size_t>(o.keyframe)], o.z).landmark;
    sub.landmarks[o.landmark] = g.landmarks[o.landmark];
  }
  DecimatedGraph d = DecimateKeyframes(sub, DecimationStride(last, settings.max_keyframes));
  LandmarkGraphOptions options = settings.solver;
  options.compute_covariance = options.joint_landmark_covariance = false;
  SolveLandmarkGraph(d.graph, options);
  SpreadDecimatedSolution(d, sub);
  std::copy(sub.poses.begin(), sub.poses.end(), g.poses.begin());
  for (const auto& [key, m] : sub.landmarks) g.landmarks[key] = m;
}

}  // namespace

LandmarkGraph ReplayGrowth(const LandmarkGraph& full, const std::vector<SE2>& frontend_poses,
                           const GrowthReplaySettings& settings) {
  const int n = static_cast<int>(full.poses.size());
  if (static_cast<int>(frontend_poses.size()) != n)
    throw std::invalid_argument("ReplayGrowth: one front-end pose per keyframe is needed");
  if (settings.solve_every_keyframes < 1)
    throw std::invalid_argument("ReplayGrowth: solve_every_keyframes must be at least 1");
  LandmarkGraph g;
  g.poses.resize(static_cast<size_t>(n));
  if (n == 0) return g;
  g.poses[0] = full.poses[0];
  if (full.odometry.size() + 1 != static_cast<size_t>(n))
    throw std::invalid_argument("ReplayGrowth: one odometry constraint between consecutive keyframes is needed");
  for (int k = 1, last_solve = 0; k < n; ++k) {
    const auto i = static_cast<size_t>(k);
    if (full.odometry[i - 1].from != k - 1)
      throw std::invalid_argument("ReplayGrowth: the odometry constraints must join keyframes 0-1, 1-2, ... in order");
    g.poses[i] = ComposedMotion(g.poses[i - 1], frontend_poses[i - 1], frontend_poses[i], full.odometry[i - 1],
                                settings.jump_gate_chi2);
    if (GrowingGraphSolveDue(k, last_solve, settings.solve_every_keyframes, settings.max_keyframes)) {
      SolveUpTo(full, k, settings, g);
      last_solve = k;
    }
  }
  // Landmarks seen only after the last solve: at their first observation.
  for (const RangeBearingConstraint& o : full.observations)
    if (full.landmarks.count(o.landmark) && !g.landmarks.count(o.landmark))
      g.landmarks[o.landmark] = InverseObservation(g.poses[static_cast<size_t>(o.keyframe)], o.z).landmark;
  return g;
}

}  // namespace slambox
