// Module plugins: every load error (missing file, not a shared library, no entry point,
// another API version, a name clash), a plugin's module bit-identical to the built-in it
// wraps, SLAMBOX_PLUGIN_PATH, `--algo all` with plugins, plugins in a sweep's workers
// (crash, timeout, resume, shards), and the shipped MRPT plugin absent.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/plugins.hpp"
#include "app/registry.hpp"
#include "core/error.hpp"
#include "core/plugin.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"
#include "tests/support/slambox_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace slambox;

const std::string kBinary = SLAMBOX_BINARY;
const std::string kPlugins = SLAMBOX_TEST_PLUGIN_DIR;
const std::string kTestPlugin = kPlugins + "/test_plugin.so";

slambox::testing::CliResult Slambox(const std::string& args) { return slambox::testing::RunSlambox(kBinary, args); }

fs::path TempDir(const std::string& name) { return slambox::testing::FreshTempDir("plugin_" + name); }

std::string Read(const fs::path& p) { return slambox::testing::ReadText(p); }

json ReadJson(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

std::string LoadError(const std::string& path) {
  try {
    LoadPlugin(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Metrics without the timing ones (runtime, real-time factor, step times differ run to run).
json Accuracy(json metrics) {
  for (auto it = metrics.begin(); it != metrics.end();)
    it = it.key().find("time") != std::string::npos ? metrics.erase(it) : std::next(it);
  return metrics;
}

TEST(Plugin, EveryLoadErrorNamesTheFileAndTheFix) {
  const std::string missing = LoadError(kPlugins + "/no_such_plugin.so");
  EXPECT_NE(missing.find("no_such_plugin.so: plugin file not found"), std::string::npos) << missing;

  const fs::path dir = TempDir("errors");
  std::ofstream(dir / "garbage.so") << "not an ELF file\n";
  const std::string garbage = LoadError((dir / "garbage.so").string());
  EXPECT_NE(garbage.find("not a loadable shared library"), std::string::npos) << garbage;
  EXPECT_NE(garbage.find("fix:"), std::string::npos) << garbage;

  const std::string noentry = LoadError(kPlugins + "/noentry_plugin.so");
  EXPECT_NE(noentry.find("not a slambox plugin: it exports no slambox_plugin_entry()"), std::string::npos) << noentry;

  const std::string version = LoadError(kPlugins + "/version_plugin.so");
  EXPECT_NE(version.find("built for slambox API version " + std::to_string(SLAMBOX_API_VERSION + 1) +
                         ", this slambox has API version " + std::to_string(SLAMBOX_API_VERSION)),
            std::string::npos)
      << version;

  const std::string clash = LoadError(kPlugins + "/clash_plugin.so");
  EXPECT_NE(clash.find("adds module 'odometry', a name the built-in module has"), std::string::npos) << clash;
  EXPECT_NE(clash.find("rename"), std::string::npos) << clash;
  fs::remove_all(dir);
}

TEST(Plugin, CliLoadErrorsExitNonZeroWithTheMessage) {
  const auto r = Slambox("run loop --plugin " + kPlugins + "/version_plugin.so --no-figures -o /tmp/unused_" +
                         std::to_string(getpid()));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("version_plugin.so: plugin built for slambox API version"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists("/tmp/unused_" + std::to_string(getpid())));
  const auto env = slambox::testing::RunSlambox("SLAMBOX_PLUGIN_PATH=/no/such/dir " + kBinary, "algorithms");
  EXPECT_EQ(env.code, 2) << env.output;
  EXPECT_NE(env.output.find("SLAMBOX_PLUGIN_PATH: '/no/such/dir' does not exist"), std::string::npos) << env.output;
}

TEST(Plugin, ModuleIsBitIdenticalToTheBuiltInItWraps) {
  LoadPlugin(kTestPlugin);
  LoadPlugin(kTestPlugin);  // a second load of the same file adds nothing
  const ModuleInfo& plugin = FindModule("test-odometry");
  const ModuleInfo& builtin = FindModule("odometry");
  EXPECT_EQ(plugin.params().size(), builtin.params().size());
  const Stream stream = Simulate(LoadScenario("loop", {"duration_s=20"}), 3);
  auto a = plugin.create({{"noise_scale", "2"}});
  auto b = builtin.create({{"noise_scale", "2"}});
  const Estimate ea = Replay(*a, stream), eb = Replay(*b, stream);
  ASSERT_EQ(ea.trajectory.size(), eb.trajectory.size());
  ASSERT_GT(ea.trajectory.size(), 100u);
  for (std::size_t i = 0; i < ea.trajectory.size(); ++i) {
    ASSERT_EQ(ea.trajectory[i].pose.x, eb.trajectory[i].pose.x) << i;
    ASSERT_EQ(ea.trajectory[i].pose.y, eb.trajectory[i].pose.y) << i;
    ASSERT_EQ(ea.trajectory[i].pose.theta, eb.trajectory[i].pose.theta) << i;
    ASSERT_TRUE(ea.trajectory[i].covariance == eb.trajectory[i].covariance) << i;
  }
  // Its parameters are checked like a built-in's.
  EXPECT_THROW(plugin.create({{"no_such_field", "1"}}), InputError);
}

TEST(Plugin, RunWithPluginAndAll) {
  const fs::path dir = TempDir("run");
  auto r = Slambox("run landmarks --seed 2 --set duration_s=10 --plugin " + kTestPlugin +
                   " --algo all --no-figures -o " + (dir / "all").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json m = ReadJson(dir / "all/metrics.json");
  for (const char* name : {"odometry", "test-odometry", "test-fault", "ekf-slam"})
    EXPECT_TRUE(m["algorithms"].contains(name)) << name << "\n" << m.dump(1);
  EXPECT_EQ(Accuracy(m["algorithms"]["odometry"]), Accuracy(m["algorithms"]["test-odometry"]));
  // A module that throws is `failed`; the others are unaffected.
  r = Slambox("run landmarks --seed 1 --set duration_s=10 --set algo.test-fault.fault=throw --plugin " + kTestPlugin +
              " --algo odometry,test-fault --no-figures -o " + (dir / "throw").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json t = ReadJson(dir / "throw/metrics.json");
  EXPECT_EQ(t["algorithms"]["test-fault"]["status"], "failed");
  EXPECT_NE(t["algorithms"]["test-fault"]["reason"].get<std::string>().find("odd seeds"), std::string::npos);
  EXPECT_EQ(t["algorithms"]["odometry"]["status"], "ok");
  // SLAMBOX_PLUGIN_PATH: a folder of plugins, listed by `algorithms`.
  fs::create_directories(dir / "plugins");
  fs::create_symlink(kTestPlugin, dir / "plugins/test_plugin.so");
  r = slambox::testing::RunSlambox("SLAMBOX_PLUGIN_PATH=" + (dir / "plugins").string() + " " + kBinary, "algorithms");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("test-odometry"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(plugin test-plugin)"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(Plugin, SweepWorkersRunPluginsWithCrashTimeoutResumeAndShards) {
  const fs::path dir = TempDir("sweep");
  fs::copy_file(kTestPlugin, dir / "test_plugin.so");
  const fs::path sweep = dir / "sweep.yaml";
  std::ofstream(sweep) << "scenarios: [landmarks]\nalgorithms: [odometry, test-odometry, test-fault]\nseeds: 4\n"
                          "set: {duration_s: 8}\ngrid:\n  algo.test-fault.fault: [crash, hang]\n"
                          "plugins: [test_plugin.so]\ntimeout_s: 3\n";
  const std::string base = kBinary + " sweep " + sweep.string() + " --no-figures ";
  auto r = slambox::testing::RunSlambox(base, "-j 2 -o " + (dir / "all").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("8 runs executed, 0 already done, 4 failed"), std::string::npos) << r.output;
  int signal = 0, timeout = 0;
  for (const auto& e : fs::directory_iterator(dir / "all/runs")) {
    const std::string f = fs::exists(e.path() / "failed.json") ? Read(e.path() / "failed.json") : "";
    signal += f.find("crashed with signal 6") != std::string::npos;
    timeout += f.find("timeout after 3 s") != std::string::npos;
    if (f.empty()) {
      const json m = ReadJson(e.path() / "metrics.json");
      EXPECT_EQ(Accuracy(m["algorithms"]["odometry"]), Accuracy(m["algorithms"]["test-odometry"]));
    }
  }
  EXPECT_EQ(signal, 2);
  EXPECT_EQ(timeout, 2);
  r = slambox::testing::RunSlambox(base, "-j 2 --resume -o " + (dir / "all").string());
  EXPECT_NE(r.output.find("0 runs executed, 8 already done"), std::string::npos) << r.output;
  // Two shards and a merge give the same results; -j 1 the same as -j 2.
  ASSERT_EQ(slambox::testing::RunSlambox(base, "-j 1 --shard 0/2 -o " + (dir / "sh").string()).code, 0);
  ASSERT_EQ(slambox::testing::RunSlambox(base, "-j 2 --shard 1/2 -o " + (dir / "sh").string()).code, 0);
  ASSERT_EQ(Slambox("sweep --no-figures --merge " + (dir / "sh").string()).code, 0);
  EXPECT_EQ(Read(dir / "all/results.csv"), Read(dir / "sh/results.csv"));
  fs::remove_all(dir);
}

TEST(Plugin, ShippedMrptPluginAbsentListsItsModulesUnavailable) {
  // A copy of the executable with the MRPT plugin's manifest but not the plugin.
  const fs::path dir = TempDir("nomrpt");
  const fs::path shipped = fs::path(kBinary).parent_path().parent_path() / "lib/slambox/plugins";
  const fs::path manifest = shipped / "slambox-mrpt.manifest.json";
  ASSERT_TRUE(fs::exists(manifest)) << manifest;
  fs::create_directories(dir / "bin");
  fs::create_directories(dir / "lib/slambox/plugins");
  fs::copy_file(kBinary, dir / "bin/slambox");
  fs::copy_file(manifest, dir / "lib/slambox/plugins/slambox-mrpt.manifest.json");
  const std::string exe = (dir / "bin/slambox").string();
  auto r = slambox::testing::RunSlambox(exe, "algorithms");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* name : {"mrpt-icp-slam", "mrpt-ekf-slam", "mrpt-rbpf-slam"}) {
    const auto at = r.output.find(std::string(name) + " ");
    ASSERT_NE(at, std::string::npos) << r.output;
    const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
    EXPECT_NE(line.find("[unavailable: plugin file"), std::string::npos) << line;
    EXPECT_NE(line.find("slambox-mrpt.so not found"), std::string::npos) << line;
  }
  // Everything else works: `all` runs the built-ins.
  r = slambox::testing::RunSlambox(exe, "run landmarks --set duration_s=8 --algo all --no-figures -o " + (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json m = ReadJson(dir / "run/metrics.json");
  EXPECT_TRUE(m["algorithms"].contains("ekf-slam"));
  EXPECT_FALSE(m["algorithms"].contains("mrpt-ekf-slam"));
  // Naming one is an error with the reason.
  r = slambox::testing::RunSlambox(exe, "run landmarks --algo mrpt-ekf-slam --no-figures -o " + (dir / "named").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("'mrpt-ekf-slam' is unavailable"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("not found"), std::string::npos) << r.output;
  // A broken plugin file: the reason is the loader's.
  std::ofstream(dir / "lib/slambox/plugins/slambox-mrpt.so") << "truncated\n";
  r = slambox::testing::RunSlambox(exe, "run landmarks --algo mrpt-ekf-slam --no-figures -o " + (dir / "named").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("not a loadable shared library"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(Plugin, ShippedMrptPluginLoadsOnlyWhenNamed) {
  // In this process: listing reads the manifest; naming a module loads the plugin.
  bool listed = false;
  for (const auto& m : ListModules())
    if (m.name == "mrpt-icp-slam") {
      listed = true;
      EXPECT_EQ(m.origin, "plugin slambox-mrpt");
      EXPECT_EQ(m.unavailable, "");
    }
  ASSERT_TRUE(listed);
  EXPECT_EQ(FindModule("mrpt-icp-slam").name, "mrpt-icp-slam");
  EXPECT_TRUE(FindModule("mrpt-icp-slam").needs.lidar);
}

}  // namespace
