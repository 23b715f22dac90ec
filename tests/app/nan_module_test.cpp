// No NaN escapes (issue 17): a module whose estimate turns non-finite is reported
// `diverged` with the first bad time in `reason`, and no file of the run folder (the
// module's .tum, estimates/, series/, metrics.json, figures) holds a NaN or an infinity.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include "app/run.hpp"
#include "core/atomic_file.hpp"
#include "core/json_io.hpp"
#include "core/tum.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;

/// Dead reckoning from the true start that turns NaN (pose, or covariance only) at t >= bad_t_s.
class PoisonedModule : public SlamModule {
 public:
  PoisonedModule(double bad_t_s, bool covariance_only) : bad_t_s_(bad_t_s), covariance_only_(covariance_only) {}
  void Start(const StreamHeader& header) override { pose_ = header.start_pose; }
  void OnOdometry(const OdometryEvent& e) override {
    pose_ = pose_ * e.delta;
    PoseEstimate p{e.t_s, pose_, Eigen::Matrix3d::Identity() * 0.01, true};
    if (e.t_s >= bad_t_s_) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      if (covariance_only_) p.covariance(1, 1) = nan;
      else p.pose.y = nan;
      landmark_.position.x() = std::numeric_limits<double>::infinity();
    }
    out_.trajectory.push_back(p);
  }
  Estimate Finish() override {
    out_.landmarks = {LandmarkEstimate{0, {1.0, 2.0}, Eigen::Matrix2d::Identity(), true}, landmark_};
    return out_;
  }

 private:
  double bad_t_s_;
  bool covariance_only_;
  SE2 pose_;
  LandmarkEstimate landmark_{1, {3.0, 4.0}, Eigen::Matrix2d::Identity(), true};
  Estimate out_;
};

std::string ReadAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void ExpectNoNonFiniteText(const fs::path& dir) {
  const std::regex bad(R"((^|[^A-Za-z_])(nan|NaN|NAN|inf|Infinity|INF)([^A-Za-z_]|$))");
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file() || entry.path().extension() == ".png") continue;
    ++files;
    const std::string text = ReadAll(entry.path());
    std::smatch m;
    EXPECT_FALSE(std::regex_search(text, m, bad)) << entry.path() << " holds '" << m.str() << "'";
  }
  EXPECT_GT(files, 5);
}

void RunPoisoned(bool covariance_only) {
  const Stream stream = Simulate(LoadScenario("landmarks", {"duration_s=6"}), 3);
  const fs::path dir = fs::temp_directory_path() / ("slambox_nan_" + std::to_string(::getpid()) +
                                                    (covariance_only ? "_cov" : "_pose"));
  fs::remove_all(dir);
  PoisonedModule module(2.5, covariance_only);
  const nlohmann::json m = ToJson(RunModuleAndWrite(module, "poisoned", stream, EvalOptions{}, dir.string()));
  ASSERT_EQ(m.value("status", ""), "diverged") << m.dump();
  const std::string reason = m.value("reason", "");
  EXPECT_NE(reason.find(covariance_only ? "non-finite covariance at t=2.5" : "non-finite pose at t=2.5"),
            std::string::npos)
      << reason;
  // The .tum keeps the poses before the first bad one (covariance-only: every pose is finite).
  const auto tum = ReadTum((dir / "poisoned.tum").string());
  ASSERT_FALSE(tum.empty());
  if (covariance_only) EXPECT_GT(tum.back().t_s, 5.0);
  else EXPECT_LT(tum.back().t_s, 2.5);
  // The rest of the run folder, as RunAndWrite writes it, then its figures.
  WriteTum((dir / "groundtruth.tum").string(), stream.groundtruth);
  WriteFileAtomic((dir / "world.json").string(),
                  nlohmann::json{{"scenario", "landmarks"}, {"seed", 3}, {"world", ToJson(stream.header.world)}}.dump());
  WriteFileAtomic((dir / "metrics.json").string(),
                  nlohmann::json{{"scenario", "landmarks"}, {"seed", 3}, {"algorithms", {{"poisoned", m}}}}.dump(1));
  const auto report = slambox::testing::RunSlambox(SLAMBOX_BINARY, "report " + dir.string());  // figures + report
  EXPECT_EQ(report.code, 0) << report.output;
  ExpectNoNonFiniteText(dir);
  fs::remove_all(dir);
}

TEST(NanModule, NonFinitePoseIsDivergedAndNoFileHoldsNan) { RunPoisoned(false); }
TEST(NanModule, NonFiniteCovarianceIsDivergedAndNoFileHoldsNan) { RunPoisoned(true); }

}  // namespace
}  // namespace slambox
