// The kidnapped robot (DESIGN.md's robot.kidnap) on the simulated `maze`: plain MCL and
// icp-localization stay lost, Augmented MCL (Thrun Table 8.3) finds the robot again.
// Not on `loop`: its corridor ring is symmetric under a half turn, so a kidnapped robot
// there may lock onto the mirror pose (measured: 3 of 8 seeds recover), which no
// LIDAR-only filter can tell apart. On `maze` 8 of 8 seeds recover.
#include <gtest/gtest.h>

#include <map>

#include "app/registry.hpp"
#include "sim/simulate.hpp"

namespace slambox {
namespace {

// The largest position error at the ground-truth times in (from_s, to_s).
double WorstError(const Estimate& e, const Stream& s, double from_s, double to_s = 1e9) {
  std::map<double, SE2> gt;
  for (const auto& g : s.groundtruth) gt[g.t_s] = g.pose;
  double worst = 0.0;
  for (const auto& p : e.trajectory)
    if (auto it = gt.find(p.t_s); p.t_s > from_s && p.t_s < to_s && it != gt.end())
      worst = std::max(worst, (p.pose.translation() - it->second.translation()).norm());
  return worst;
}

TEST(MclKidnap, AugmentedMclRecoversPlainMclDoesNot) {
  // At 60 s the robot heads west at (19.7, 14.7) for waypoint (19.2, 14.6); it is put
  // 4.7 m further west, facing east, and drives back to that waypoint.
  const Stream s = Simulate(LoadScenario("maze", {"robot.kidnap.at_s=60", "robot.kidnap.to.x=15",
                                                   "robot.kidnap.to.y=15", "robot.kidnap.to.theta_deg=0"}),
                            1);
  const auto run = [&](const std::string& name, const ParamOverrides& o) {
    auto module = FindModule(name).create(o);
    return Replay(*module, s);
  };
  const Estimate plain = run("mcl", {});
  const Estimate augmented = run("mcl", {{"recovery_alpha_slow", "0.001"}, {"recovery_alpha_fast", "0.1"}});
  const Estimate icp = run("icp-localization", {});
  for (const Estimate* e : {&plain, &augmented, &icp}) EXPECT_LT(WorstError(*e, s, 0.0, 59.0), 0.1) << (e == &icp ? "icp" : "mcl");
  EXPECT_LT(WorstError(augmented, s, 100.0), 0.1);  // found again within 40 s of the kidnap
  EXPECT_GT(WorstError(plain, s, 100.0), 1.0);
  EXPECT_GT(WorstError(icp, s, 100.0), 1.0);
  ASSERT_TRUE(augmented.diagnostics.count("random_particles"));
  double injected = 0;
  for (const auto& [t, n] : augmented.diagnostics.at("random_particles")) injected += t > 60.0 ? n : 0.0;
  EXPECT_GT(injected, 50);
}

}  // namespace
}  // namespace slambox
