// A landmark run made by another simulator (the 2D-I-SLSJF release's sim_535: 3 m, 180 deg
// detector, 1.2 deg of heading noise per step, an open path with no loop) replayed end to end:
// `slambox convert islsjf-sim`, then `run` with the ids known and hidden. Nothing of slambox
// was tuned on it. Skips without the public data. Measured values and commands:
// slam/README_landmark_slam.md, "Held out: the 2D-I-SLSJF simulation".
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/support/public_data.hpp"
#include "tests/support/slambox_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json Metrics(const fs::path& run) {
  std::ifstream in(run / "metrics.json");
  return json::parse(in).at("algorithms");
}

TEST(IslsjfAccuracy, LandmarkModulesOnSim535) {
  const std::string data = slambox::testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "landmark/sim_535");
  if (data.empty()) GTEST_SKIP() << "landmark/sim_535 not found; set SLAMBOX_DATA";
  const fs::path dir = slambox::testing::FreshTempDir("islsjf_accuracy");
  const std::string stream = (dir / "sim535.stream").string();
  const auto run = [&](const std::string& args) { return slambox::testing::RunSlambox(SLAMBOX_BINARY, args); };
  ASSERT_EQ(run("convert islsjf-sim " + data + " -o " + stream).code, 0);
  const auto known = run("run " + stream + " --algo odometry,ekf-slam,graphslam --no-figures -q -o " + (dir / "known").string());
  ASSERT_EQ(known.code, 0) << known.output;
  const auto hidden = run("run " + stream + " --algo ekf-slam,graphslam --hide-landmark-ids --no-figures -q -o " + (dir / "hidden").string());
  ASSERT_EQ(hidden.code, 0) << hidden.output;
  const json k = Metrics(dir / "known"), h = Metrics(dir / "hidden");
  // Measured: aligned ATE RMSE odometry 0.713 m; known ids ekf-slam 0.313, graphslam 0.251;
  // hidden ids 0.330 / 0.270 with association_agreement 0.9788 both, 28 of 28 beacons matched,
  // none spurious. Bounds: the measured value plus ~30 %, agreement minus 0.02.
  const double odometry = k.at("odometry").at("ate_aligned_rmse_m").get<double>();
  EXPECT_NEAR(odometry, 0.713, 0.001);  // the stream itself has not changed
  struct Expected { const json& metrics; const char* module; double max_aligned_m; };
  for (const Expected& x : {Expected{k, "ekf-slam", 0.40}, Expected{k, "graphslam", 0.33}, Expected{h, "ekf-slam", 0.43},
                            Expected{h, "graphslam", 0.35}}) {
    const json& a = x.metrics.at(x.module);
    EXPECT_EQ(a.at("status"), "ok") << x.module;
    EXPECT_LT(a.at("ate_aligned_rmse_m").get<double>(), x.max_aligned_m) << x.module << " " << a.dump();
    EXPECT_EQ(a.at("landmark_matched").get<int>(), 28) << x.module;
    EXPECT_EQ(a.at("landmark_spurious").get<int>(), 0) << x.module;
  }
  for (const char* module : {"ekf-slam", "graphslam"})
    EXPECT_GE(h.at(module).at("association_agreement").get<double>(), 0.96) << module;
}

}  // namespace
