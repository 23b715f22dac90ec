// End-to-end sweeps through the real binary: identical results at any -j, resume after
// SIGKILL, crashing and hanging runs recorded as failed, --check on a planted regression.
#include <gtest/gtest.h>

#include "tests/support/slambox_cli.hpp"
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace {

namespace fs = std::filesystem;

const std::string kBinary = SLAMBOX_BINARY;

fs::path TempDir(const std::string& name) { return slambox::testing::FreshTempDir("sweep_" + name); }

std::string Read(const fs::path& p) { return slambox::testing::ReadText(p); }

int Shell(const std::string& cmd) {
  const int status = std::system((cmd + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A short sweep: 4 seeds of a 12 s landmarks run, odometry only.
fs::path WriteSweep(const fs::path& dir) {
  const fs::path p = dir / "sweep.yaml";
  std::ofstream(p) << "scenarios: [landmarks]\nalgorithms: [odometry]\nseeds: 4\nset: {duration_s: 12}\n"
                      "grid:\n  sensors.odometry.rate_hz: [25, 50]\n";
  return p;
}

TEST(SweepRun, ResultsAreIdenticalAtAnyJobCount) {
  const fs::path dir = TempDir("jobs");
  const fs::path sweep = WriteSweep(dir);
  ASSERT_EQ(Shell(kBinary + " sweep " + sweep.string() + " -j 1 --no-figures -o " + (dir / "j1").string()), 0);
  ASSERT_EQ(Shell(kBinary + " sweep " + sweep.string() + " -j 2 --no-figures -o " + (dir / "j2").string()), 0);
  const std::string a = Read(dir / "j1/results.csv"), b = Read(dir / "j2/results.csv");
  EXPECT_EQ(a, b);
  EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), 1 + 8) << a;  // header + 2 grid points x 4 seeds
  EXPECT_NE(Read(dir / "j1/summary.md").find("landmarks"), std::string::npos);
  // Without --resume an existing result folder is refused.
  EXPECT_NE(Shell(kBinary + " sweep " + sweep.string() + " --no-figures -o " + (dir / "j1").string()), 0);
  fs::remove_all(dir);
}

TEST(SweepRun, ResumeAfterSigkillGivesIdenticalResults) {
  const fs::path dir = TempDir("resume");
  const fs::path sweep = WriteSweep(dir);
  ASSERT_EQ(Shell(kBinary + " sweep " + sweep.string() + " -j 2 --no-figures -o " + (dir / "whole").string()), 0);
  std::mt19937 rng(7);
  const std::string out = (dir / "killed").string();
  for (int attempt = 0; attempt < 3; ++attempt) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      freopen("/dev/null", "w", stderr);
      freopen("/dev/null", "w", stdout);
      execl(kBinary.c_str(), kBinary.c_str(), "sweep", sweep.c_str(), "-j", "2", "--no-figures", "--resume", "-o",
            out.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    usleep(std::uniform_int_distribution<int>(50, 600)(rng) * 1000);
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
  ASSERT_EQ(Shell(kBinary + " sweep " + sweep.string() + " -j 2 --no-figures --resume -o " + out), 0);
  EXPECT_EQ(Read(dir / "whole/results.csv"), Read(fs::path(out) / "results.csv"));
  fs::remove_all(dir);
}

TEST(SweepRun, CrashingAndHangingRunsAreRecordedAsFailed) {
  const fs::path dir = TempDir("faults");
  const fs::path sweep = WriteSweep(dir);
  const fs::path worker = dir / "worker.sh";
  std::ofstream(worker) << "#!/bin/bash\n"
                           "case \" $* \" in\n"
                           "  *' --seed 1 '*) sleep 600 ;;\n"
                           "  *' --seed 2 '*) kill -SEGV $$ ;;\n"
                           "esac\n"
                           "exec " << kBinary << " \"$@\"\n";
  fs::permissions(worker, fs::perms::owner_all);
  ASSERT_EQ(Shell(kBinary + " sweep " + sweep.string() + " -j 2 --no-figures --timeout 3 --worker-exe " +
                  worker.string() + " -o " + (dir / "out").string()),
            0);
  const std::string csv = Read(dir / "out/results.csv");
  int ok = 0, failed = 0;
  for (std::size_t p = 0; (p = csv.find(",odometry,", p)) != std::string::npos; ++p)
    (csv.compare(p + 10, 2, "ok") == 0 ? ok : failed)++;
  EXPECT_EQ(ok, 4) << csv;
  EXPECT_EQ(failed, 4) << csv;
  bool saw_timeout = false, saw_signal = false;
  for (const auto& entry : fs::directory_iterator(dir / "out/runs")) {
    const std::string f = Read(entry.path() / "failed.json");
    saw_timeout |= f.find("timeout after 3 s") != std::string::npos;
    saw_signal |= f.find("crashed with signal 11") != std::string::npos;
  }
  EXPECT_TRUE(saw_timeout);
  EXPECT_TRUE(saw_signal);
  fs::remove_all(dir);
}

TEST(SweepRun, CheckFailsOnAPlantedRegression) {
  const fs::path dir = TempDir("check");
  const fs::path sweep = WriteSweep(dir);
  const std::string out = (dir / "out").string();
  ASSERT_EQ(Shell(kBinary + " sweep " + sweep.string() + " -j 2 --no-figures -o " + out), 0);
  // The baseline is the same sweep: passes. A baseline with halved errors: fails with 4.
  EXPECT_EQ(Shell(kBinary + " sweep --merge " + out + " --no-figures --check " + out + "/results.csv"), 0);
  std::string csv = Read(fs::path(out) / "results.csv");
  std::istringstream lines(csv);
  std::string line, planted;
  std::getline(lines, line);
  planted = line + "\n";
  const auto header_end = line;
  while (std::getline(lines, line)) {
    // Halve the ATE column (column 6 = first metric, ate_rmse_m) of every row.
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string x; std::getline(s, x, ',');) f.push_back(x);
    f[6] = std::to_string(std::stod(f[6]) / 2);
    for (std::size_t i = 0; i < f.size(); ++i) planted += (i ? "," : "") + f[i];
    planted += "\n";
  }
  std::ofstream(dir / "baseline.csv") << planted;
  ASSERT_NE(header_end.find(",ate_rmse_m,"), std::string::npos) << header_end;
  EXPECT_EQ(Shell(kBinary + " sweep --merge " + out + " --no-figures --check " + (dir / "baseline.csv").string()), 4);
  fs::remove_all(dir);
}

TEST(SweepRun, ListAndEmitSlurm) {
  const fs::path dir = TempDir("list");
  const fs::path sweep = WriteSweep(dir);
  const std::string list_file = (dir / "list.txt").string();
  ASSERT_EQ(std::system((kBinary + " sweep " + sweep.string() + " --list > " + list_file).c_str()), 0);
  const std::string list = Read(list_file);
  EXPECT_EQ(std::count(list.begin(), list.end(), '\n'), 8);
  const std::string job = (dir / "job.sh").string();
  ASSERT_EQ(std::system((kBinary + " sweep " + sweep.string() + " -o " + (dir / "o").string() +
                         " --emit-slurm --shards 3 > " + job).c_str()),
            0);
  const std::string script = Read(job);
  EXPECT_NE(script.find("#SBATCH --array=0-2"), std::string::npos) << script;
  EXPECT_NE(script.find("--shard \"${SLURM_ARRAY_TASK_ID}/3\""), std::string::npos) << script;
  fs::remove_all(dir);
}

}  // namespace
