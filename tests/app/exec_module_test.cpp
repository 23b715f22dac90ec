// `exec` modules end to end (docs/exec_protocol.md): the Python dead-reckoning example
// gives bit-identical metrics to the built-in `odometry`; misbehaving children each get a
// clear status while the other modules go on; declarations, export and exec-check.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/slambox_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kBinary = SLAMBOX_BINARY;
const std::string kSource = SLAMBOX_SOURCE_DIR;
const std::string kExample = kSource + "/examples/python/py-odometry.yaml";
const std::string kChildren = kSource + "/tests/app/exec_children";

slambox::testing::CliResult Slambox(const std::string& args) {
  return slambox::testing::RunSlambox("SLAMBOX_EXEC_PATH=" + kChildren + " " + kBinary, args);
}

fs::path TempDir(const std::string& name) {
  const fs::path dir = slambox::testing::FreshTempDir("exec_" + name);
  fs::remove_all(dir);  // the commands under test create it
  return dir;
}

std::string Read(const fs::path& p) { return slambox::testing::ReadText(p); }

json ReadJson(const fs::path& p) { return json::parse(Read(p)); }

/// Wall-clock keys differ between any two runs; everything else must be equal.
json WithoutTimings(json m) {
  for (auto it = m.begin(); it != m.end();)
    if (it.key().find("time") != std::string::npos || it.key().find("runtime") != std::string::npos)
      it = m.erase(it);
    else
      ++it;
  return m;
}

TEST(ExecModule, PythonDeadReckoningIsBitIdenticalToTheBuiltIn) {
  const fs::path dir = TempDir("python");
  const auto r = Slambox("run loop --seed 3 --set duration_s=60 --algo odometry,exec:" + kExample +
                         " --no-figures -q -o " + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json m = ReadJson(dir / "metrics.json")["algorithms"];
  ASSERT_TRUE(m.contains("exec:py-odometry")) << m.dump(1);
  EXPECT_EQ(m["exec:py-odometry"]["status"], "ok") << m["exec:py-odometry"].dump(1);
  EXPECT_EQ(WithoutTimings(m["exec:py-odometry"]), WithoutTimings(m["odometry"]));
  EXPECT_TRUE(m["odometry"]["anees"].is_number());  // covariances went through, exactly
  // The trajectories and covariances, bit for bit (shortest round-trip text both ways).
  EXPECT_EQ(Read(dir / "exec:py-odometry.tum"), Read(dir / "odometry.tum"));
  EXPECT_EQ(ReadJson(dir / "estimates" / "exec:py-odometry.json")["trajectory"],
            ReadJson(dir / "estimates" / "odometry.json")["trajectory"]);
}

TEST(ExecModule, ParametersPassThroughSet) {
  const fs::path dir = TempDir("params");
  const auto r = Slambox("run loop --set duration_s=20 --algo odometry,exec:" + kExample +
                         " --set algo.odometry.noise_scale=4 --set algo.exec:py-odometry.noise_scale=4 --no-figures -q -o " +
                         dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json m = ReadJson(dir / "metrics.json")["algorithms"];
  EXPECT_EQ(WithoutTimings(m["exec:py-odometry"]), WithoutTimings(m["odometry"]));
  const json base = ReadJson(dir / "estimates" / "odometry.json");
  const auto bad = Slambox("run loop --set duration_s=5 --algo exec:" + kExample +
                           " --set algo.exec:py-odometry.noise_scale=abc --no-figures -q -o " + dir.string());
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.output.find("noise_scale"), std::string::npos) << bad.output;
  const auto unknown = Slambox("run loop --set duration_s=5 --algo exec:" + kExample +
                               " --set algo.exec:py-odometry.particles=3 --no-figures -q -o " + dir.string());
  EXPECT_NE(unknown.code, 0);
  EXPECT_NE(unknown.output.find("particles"), std::string::npos) << unknown.output;
}

TEST(ExecModule, EveryParameterTypeReachesTheChildTyped) {
  const fs::path dir = TempDir("types");
  const std::string sets =
      " --set algo.exec:params.gain=2.5 --set algo.exec:params.n=7 --set algo.exec:params.on=true"
      " --set algo.exec:params.mode=exact";
  const auto r = Slambox("run loop --set duration_s=3 --algo exec:params" + sets + " --no-figures -q -o " + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(ReadJson(dir / "metrics.json")["algorithms"]["exec:params"]["status"], "ok") << r.output;
  const auto defaults = Slambox("run loop --set duration_s=3 --algo exec:params --no-figures -q -o " + dir.string());
  EXPECT_EQ(ReadJson(dir / "metrics.json")["algorithms"]["exec:params"]["status"], "failed") << defaults.output;
  const auto listing = Slambox("algorithms --params exec:params");
  for (const char* row : {"algo.exec:params.gain  double  1", "algo.exec:params.n     int     3",
                          "algo.exec:params.on    bool    false", "algo.exec:params.mode  enum    fast"})
    EXPECT_NE(listing.output.find(row), std::string::npos) << row << "\n" << listing.output;
  const auto bad = Slambox("run loop --set duration_s=3 --algo exec:params --set algo.exec:params.mode=slow -o " +
                           dir.string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("slow"), std::string::npos) << bad.output;
}

TEST(ExecModule, EachMisbehavingChildGetsAClearStatusAndTheOthersGoOn) {
  const fs::path dir = TempDir("children");
  const auto r = Slambox(
      "run loop --set duration_s=20 --algo odometry,exec:crash,exec:exit3,exec:hang,exec:garbage,exec:nan,"
      "exec:flood,exec:quiet-exit,exec:" +
      kExample + " --no-figures -q -o " + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json m = ReadJson(dir / "metrics.json")["algorithms"];
  const auto expect = [&](const std::string& name, const std::string& status, std::vector<std::string> needles) {
    ASSERT_TRUE(m.contains(name)) << name;
    EXPECT_EQ(m[name]["status"], status) << name << ": " << m[name].dump(1);
    const std::string reason = m[name].value("reason", "");
    for (const auto& n : needles) EXPECT_NE(reason.find(n), std::string::npos) << name << ": " << reason;
  };
  expect("odometry", "ok", {});
  expect("exec:py-odometry", "ok", {});
  expect("exec:flood", "ok", {});  // 32 MiB of stderr: no deadlock
  expect("exec:crash", "failed", {"signal 11", "stderr tail", "about to segfault"});
  expect("exec:exit3", "failed", {"exit status 3", "before", "giving up"});
  expect("exec:quiet-exit", "failed", {"exited before", "exit status 0"});
  expect("exec:hang", "failed", {"no progress", "killed", "child hang: started"});
  expect("exec:garbage", "failed", {"stdout line 2", "hello, I am not JSON"});
  expect("exec:nan", "diverged", {"stdout line 2", "non-finite pose"});
  EXPECT_EQ(WithoutTimings(m["exec:py-odometry"]), WithoutTimings(m["odometry"]));
}

TEST(ExecModule, InASweepAtJ2TheExecModuleMatchesTheBuiltInRowForRow) {
  const fs::path dir = TempDir("sweep");
  fs::create_directories(dir);
  std::ofstream(dir / "sweep.yaml") << "scenarios: [loop]\nalgorithms: [odometry, exec:" << kExample
                                    << "]\nseeds: 2\nset: {duration_s: 15}\n";
  const auto r = Slambox("sweep " + (dir / "sweep.yaml").string() + " -j2 --no-figures -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "out" / "results.csv");
  std::map<std::string, std::string> odometry, exec;  // seed -> the row after "algorithm,"
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> f;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(cell);
    if (f.size() < 5) continue;
    const std::string rest = line.substr(line.find("," + f[3] + ",") + f[3].size() + 2);
    if (f[3] == "odometry") odometry[f[2]] = rest;
    if (f[3] == "exec:py-odometry") exec[f[2]] = rest;
  }
  ASSERT_EQ(odometry.size(), 2u) << r.output;
  EXPECT_EQ(exec, odometry);
  EXPECT_EQ(odometry.begin()->second.rfind("ok,", 0), 0u);
}

TEST(ExecModule, AllWithAnExecModule) {
  const fs::path dir = TempDir("all");
  const auto r = Slambox("run loop --set duration_s=8 --algo all,exec:crash,exec:" + kExample +
                         " --no-figures -q -o " + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json m = ReadJson(dir / "metrics.json")["algorithms"];
  for (const char* name : {"odometry", "icp-odometry", "icp-poseslam", "exec:py-odometry"})
    EXPECT_EQ(m[name]["status"], "ok") << name << ": " << m[name].dump(1);
  EXPECT_EQ(m["exec:crash"]["status"], "failed");
}

TEST(ExecModule, BadDeclarationsAndNamesAreClearErrors) {
  const fs::path dir = TempDir("decl");
  fs::create_directories(dir);
  const auto missing = Slambox("run loop --set duration_s=2 --algo exec:no-such-module -o " + (dir / "o").string());
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.output.find("no-such-module.yaml"), std::string::npos) << missing.output;
  EXPECT_NE(missing.output.find("SLAMBOX_EXEC_PATH"), std::string::npos) << missing.output;
  std::ofstream(dir / "bad.yaml") << "version: 1\ncommand: [/bin/true]\nneeds: [odometry, sonar]\n";
  const auto bad = Slambox("run loop --set duration_s=2 --algo exec:" + (dir / "bad.yaml").string() + " -o " + (dir / "o").string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("bad.yaml:3"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("sonar"), std::string::npos) << bad.output;
  std::ofstream(dir / "typo.yaml") << "version: 1\ncommand: [/bin/true]\ncomand: [x]\n";
  const auto typo = Slambox("run loop --set duration_s=2 --algo exec:" + (dir / "typo.yaml").string() + " -o " + (dir / "o").string());
  EXPECT_NE(typo.output.find("typo.yaml:3: unknown key 'comand'"), std::string::npos) << typo.output;
  fs::create_directories(dir / "other");
  fs::copy_file(kExample, dir / "other" / "py-odometry.yaml");
  const auto clash = Slambox("run loop --set duration_s=2 --algo exec:" + kExample + ",exec:" +
                             (dir / "other" / "py-odometry.yaml").string() + " -o " + (dir / "o").string());
  EXPECT_EQ(clash.code, 2);
  EXPECT_NE(clash.output.find("two declarations are both named exec:py-odometry"), std::string::npos) << clash.output;
  std::ofstream(dir / "nocmd.yaml") << "version: 1\ncommand: [/nonexistent/program]\nneeds: [odometry]\n";
  const auto nocmd = Slambox("run loop --set duration_s=2 --algo odometry,exec:" + (dir / "nocmd.yaml").string() +
                             " --no-figures -q -o " + (dir / "o").string());
  ASSERT_EQ(nocmd.code, 0) << nocmd.output;
  const json m = ReadJson(dir / "o" / "metrics.json")["algorithms"];
  EXPECT_EQ(m["exec:nocmd"]["status"], "failed");
  EXPECT_NE(m["exec:nocmd"]["reason"].get<std::string>().find("No such file"), std::string::npos);
  EXPECT_EQ(m["odometry"]["status"], "ok");
}

TEST(ExecModule, AlgorithmsListsTheDeclarationsOnTheExecPath) {
  const auto r = Slambox("algorithms");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("exec:crash"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("test child (hang)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("icp-poseslam"), std::string::npos) << r.output;
  const auto p = Slambox("algorithms --params exec:" + kExample);
  EXPECT_NE(p.output.find("algo.exec:py-odometry.noise_scale  double  1"), std::string::npos) << p.output;
}

TEST(ExecModule, DeclaredOnTheCommandLine) {
  const fs::path dir = TempDir("inline");
  const auto r = Slambox("run loop --set duration_s=10 --algo odometry,exec:mine --exec 'mine:odometry=/usr/bin/python3 " +
                         kSource + "/examples/python/dead_reckoning.py' --no-figures -q -o " + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json m = ReadJson(dir / "metrics.json")["algorithms"];
  EXPECT_EQ(WithoutTimings(m["exec:mine"]), WithoutTimings(m["odometry"]));
  const auto bad = Slambox("run loop --set duration_s=2 --algo exec:mine --exec 'mine:sonar=true' -o " + dir.string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("unknown sensor need 'sonar'"), std::string::npos) << bad.output;
}

TEST(ExecModule, ConformanceCheckPassesTheExampleAndFailsBrokenChildren) {
  const auto ok = Slambox("exec-check " + kExample);
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_NE(ok.output.find("exec-check: conforms"), std::string::npos) << ok.output;
  const auto bad = Slambox("exec-check garbage");
  EXPECT_EQ(bad.code, 1) << bad.output;
  EXPECT_NE(bad.output.find("FAIL"), std::string::npos) << bad.output;
}

TEST(Export, JsonlIsTheProtocolsEventSchemaAndCsvHasOneRowPerEvent) {
  const fs::path dir = TempDir("export");
  fs::create_directories(dir);
  const std::string stream = (dir / "s.stream").string();
  ASSERT_EQ(Slambox("simulate loop --set duration_s=5 --set sensors.gyro.rate_hz=20 -o " + stream).code, 0);
  const auto jl = Slambox("export " + stream + " --format jsonl -o " + (dir / "s.jsonl").string());
  ASSERT_EQ(jl.code, 0) << jl.output;
  const auto csv = Slambox("export " + stream + " --format csv -o " + (dir / "s.csv").string());
  ASSERT_EQ(csv.code, 0) << csv.output;
  std::ifstream in(dir / "s.jsonl");
  std::vector<json> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(json::parse(l));
  ASSERT_GT(lines.size(), 3u);
  EXPECT_EQ(lines.front()["type"], "header");
  EXPECT_TRUE(lines.front().contains("world"));
  EXPECT_EQ(lines.back()["type"], "finish");
  std::map<std::string, int> types;
  for (std::size_t i = 1; i + 1 < lines.size(); ++i) ++types[lines[i]["type"].get<std::string>()];
  EXPECT_GT(types["odometry"], 0);
  EXPECT_GT(types["scan"], 0);
  EXPECT_GT(types["gyro"], 0);
  std::ifstream c(dir / "s.csv");
  std::string header;
  std::getline(c, header);
  EXPECT_EQ(header.rfind("type,t_s,dx_m,dy_m,dtheta_rad", 0), 0u);
  std::size_t rows = 0;
  for (std::string l; std::getline(c, l); ++rows)
    EXPECT_EQ(std::count(l.begin(), l.end(), ','), std::count(header.begin(), header.end(), ',')) << l.substr(0, 80);
  EXPECT_EQ(rows, lines.size() - 2);
  const auto bad = Slambox("export " + stream + " --format xml -o " + (dir / "s.xml").string());
  EXPECT_NE(bad.code, 0);
  EXPECT_FALSE(fs::exists(dir / "s.xml"));
}

}  // namespace
