// ModuleInfo::in_all = false (expensive peers are run only when named): `all` leaves the
// module out of `run --algo all`, a sweep's `algorithms: [all]` and its sweep.json, naming it
// runs it, the plugin manifest carries the flag, and `slambox algorithms` says so. The
// module is the test plugin's `test-named-only` (tests/plugins/test_plugin.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app/plugins.hpp"
#include "app/registry.hpp"
#include "app/run_modules.hpp"
#include "core/error.hpp"
#include "tests/support/slambox_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace slambox;

const std::string kBinary = SLAMBOX_BINARY;
const std::string kTestPlugin = std::string(SLAMBOX_TEST_PLUGIN_DIR) + "/test_plugin.so";

json ReadJson(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

SensorSuite OdometryOnly() {
  SensorSuite s;
  s.odometry = OdometryConfig{};
  return s;
}

TEST(NamedOnly, AllLeavesItOutNamingItRunsIt) {
  LoadPlugin(kTestPlugin);
  const std::vector<std::string> all = ResolveAlgorithms({"all"}, OdometryOnly());
  EXPECT_NE(std::find(all.begin(), all.end(), "test-odometry"), all.end());
  EXPECT_EQ(std::find(all.begin(), all.end(), "test-named-only"), all.end());
  EXPECT_EQ(ResolveAlgorithms({"test-named-only"}, OdometryOnly()), std::vector<std::string>{"test-named-only"});
  const std::vector<std::string> both = ResolveAlgorithms({"all", "test-named-only"}, OdometryOnly());
  EXPECT_NE(std::find(both.begin(), both.end(), "test-named-only"), both.end());
  bool listed = false;
  for (const auto& m : ListModules()) {
    if (m.name == "test-named-only") {
      listed = true;
      EXPECT_FALSE(m.in_all);
    }
    if (m.name == "test-odometry" || m.name == "odometry") {
      EXPECT_TRUE(m.in_all) << m.name;
    }
  }
  EXPECT_TRUE(listed);
}

TEST(NamedOnly, ManifestCarriesTheFlag) {
  const LoadedPlugin plugin = OpenPlugin(kTestPlugin);
  const fs::path dir = slambox::testing::FreshTempDir("named_only_manifest");
  std::ofstream(dir / "test_plugin.manifest.json") << ManifestJson(plugin, "test_plugin.so");
  const std::vector<ManifestModule> read = ReadManifests(dir.string());
  ASSERT_EQ(read.size(), 3u);
  for (const auto& m : read) EXPECT_EQ(m.in_all, m.name != "test-named-only") << m.name;
  // A manifest without the flag is from before API version 4: malformed, with the reason.
  json doc = json::parse(ManifestJson(plugin, "test_plugin.so"));
  doc["modules"][0].erase("in_all");
  std::ofstream(dir / "test_plugin.manifest.json") << doc.dump();
  EXPECT_THROW(ReadManifests(dir.string()), InputError);
  fs::remove_all(dir);
}

TEST(NamedOnly, CommandLineRunSweepAndListing) {
  const fs::path dir = slambox::testing::FreshTempDir("named_only_cli");
  const std::string plugin = " --plugin " + kTestPlugin;
  auto r = slambox::testing::RunSlambox(kBinary, "algorithms" + plugin);
  ASSERT_EQ(r.code, 0) << r.output;
  for (const auto& [name, named_only] : {std::pair{"test-named-only ", true}, std::pair{"test-odometry ", false}}) {
    const auto at = r.output.find(name);
    ASSERT_NE(at, std::string::npos) << r.output;
    const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
    EXPECT_EQ(line.find("(named only, not in all)") != std::string::npos, named_only) << line;
  }
  r = slambox::testing::RunSlambox(kBinary, "run landmarks --set duration_s=5 --set sensors.landmarks=null --algo all" +
                                                plugin + " --no-figures -q -o " + (dir / "all").string());
  ASSERT_EQ(r.code, 0) << r.output;
  json m = ReadJson(dir / "all/metrics.json");
  EXPECT_TRUE(m["algorithms"].contains("test-odometry")) << m.dump(1);
  EXPECT_FALSE(m["algorithms"].contains("test-named-only")) << m.dump(1);
  r = slambox::testing::RunSlambox(kBinary, "run landmarks --set duration_s=5 --algo test-named-only" + plugin +
                                                " --no-figures -q -o " + (dir / "named").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(ReadJson(dir / "named/metrics.json")["algorithms"].contains("test-named-only"));
  std::ofstream(dir / "sweep.yaml") << "scenarios: [landmarks]\nalgorithms: [all]\nseeds: 1\n"
                                       "set: {duration_s: 5, sensors.landmarks: null}\nplugins: [" + kTestPlugin + "]\n";
  r = slambox::testing::RunSlambox(kBinary, "sweep " + (dir / "sweep.yaml").string() + " --no-figures -o " +
                                                (dir / "sweep").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json sweep = ReadJson(dir / "sweep/sweep.json");
  EXPECT_TRUE(sweep["modules"].contains("test-odometry")) << sweep.dump(1);
  EXPECT_FALSE(sweep["modules"].contains("test-named-only")) << sweep.dump(1);
  EXPECT_EQ(slambox::testing::ReadText(dir / "sweep/results.csv").find("test-named-only"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
