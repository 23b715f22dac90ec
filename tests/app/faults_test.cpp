// Faults (issue 17): commands killed with SIGKILL at random moments leave every output
// file either as it was or complete; a full disk (ENOSPC on a small tmpfs) gives a clear
// error and no partial file; a second sweep on a running sweep's folder refuses.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "app/sweep_lock.hpp"
#include "core/error.hpp"
#include "core/stream_io.hpp"
#include "core/tum.hpp"
#include "slam/g2o_io.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;
const std::string kBinary = SLAMBOX_BINARY;

fs::path TempDir(const std::string& name) { return slambox::testing::FreshTempDir("faults_" + name); }

std::string Read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// A file as a reader sees it: complete (parses to the end) or not.
void ExpectComplete(const fs::path& p) {
  const std::string ext = p.extension().string(), bytes = Read(p);
  SCOPED_TRACE(p.string());
  if (ext == ".json") {
    EXPECT_TRUE(nlohmann::json::accept(bytes));
  } else if (ext == ".tum") {
    EXPECT_NO_THROW(ReadTum(p.string()));
    EXPECT_TRUE(bytes.empty() || bytes.back() == '\n');
  } else if (ext == ".stream") {
    EXPECT_NO_THROW(ReadStream(p.string()));
  } else if (ext == ".g2o") {
    EXPECT_NO_THROW(ReadPoseGraph(p.string()));
  } else if (ext == ".png") {
    ASSERT_GE(bytes.size(), 12u);
    EXPECT_EQ(bytes.substr(bytes.size() - 8, 4), "IEND");
  } else if (ext == ".svg") {
    EXPECT_TRUE(EndsWith(bytes, "</svg>\n") || EndsWith(bytes, "</svg>"));
  } else if (ext == ".html") {
    EXPECT_TRUE(EndsWith(bytes, "</html>\n") || EndsWith(bytes, "</html>"));
  } else if (ext == ".csv" || ext == ".md") {
    EXPECT_TRUE(bytes.empty() || bytes.back() == '\n');
  }
}

/// Every file under `dir` (or the file `dir`) except temporaries is complete.
int ExpectAllComplete(const fs::path& path) {
  int n = 0;
  if (fs::is_regular_file(path)) {
    ExpectComplete(path);
    return 1;
  }
  if (!fs::exists(path)) return 0;
  for (const auto& e : fs::recursive_directory_iterator(path)) {
    if (!e.is_regular_file() || e.path().filename().string().find(".tmp.") != std::string::npos) continue;
    if (e.path().filename() == ".lock") continue;
    ExpectComplete(e.path());
    ++n;
  }
  return n;
}

pid_t Spawn(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    freopen("/dev/null", "w", stdout);
    freopen("/dev/null", "w", stderr);
    std::vector<char*> argv{const_cast<char*>(kBinary.c_str())};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(kBinary.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

/// Runs `args` to completion once (the "old" output), then kills it `kills` times at
/// random moments within `window_ms`: each time every output file must be complete.
void KillAtRandom(const std::vector<std::string>& args, const fs::path& output, int kills, int window_ms,
                  unsigned seed) {
  const pid_t first = Spawn(args);
  int status = 0;
  waitpid(first, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the command itself fails";
  std::mt19937 rng(seed);
  for (int k = 0; k < kills; ++k) {
    const pid_t pid = Spawn(args);
    std::this_thread::sleep_for(std::chrono::milliseconds(std::uniform_int_distribution<int>(0, window_ms)(rng)));
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    EXPECT_GT(ExpectAllComplete(output), 0) << "kill " << k;
  }
}

std::string RingGraph() {
  std::ostringstream g;
  const int n = 300;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    g << "VERTEX_SE2 " << i << " " << 10 * std::cos(a) + 0.01 * (i % 7) << " " << 10 * std::sin(a) << " "
      << a + M_PI / 2 << "\n";
  }
  const double step = 2 * 10 * std::sin(M_PI / n);
  for (int i = 0; i < n; ++i)
    g << "EDGE_SE2 " << i << " " << (i + 1) % n << " " << step << " 0 " << 2 * M_PI / n << " 100 0 0 100 0 400\n";
  return g.str();
}

TEST(Faults, SigkillLeavesOldOrCompleteFiles) {
  const fs::path dir = TempDir("kill");
  // simulate (a stream), run (a run folder with figures), report, optimize -o, convert.
  KillAtRandom({"simulate", "landmarks", "--set", "duration_s=20", "-o", (dir / "s.stream").string()}, dir / "s.stream",
               4, 400, 1);
  KillAtRandom({"run", (dir / "s.stream").string(), "--algo", "odometry,ekf-slam", "-o", (dir / "run").string()},
               dir / "run", 4, 1500, 2);
  KillAtRandom({"report", (dir / "run").string(), "--rerender"}, dir / "run", 4, 1500, 3);
  std::ofstream(dir / "ring.g2o") << RingGraph();
  KillAtRandom({"optimize", (dir / "ring.g2o").string(), "-o", (dir / "opt.g2o").string()}, dir / "opt.g2o", 4, 300, 4);
  std::ofstream log(dir / "log.clf");
  for (int i = 0; i < 3000; ++i) {
    log << "ODOM " << 0.01 * i << " 0 0 0 0 0 " << 0.1 * i << " host 0\n";
    log << "FLASER 5 1 2 3 4 5 " << 0.01 * i << " 0 0 " << 0.01 * i << " 0 0 " << 0.1 * i + 0.05 << " host 0\n";
  }
  log.close();
  KillAtRandom({"convert", "carmen", (dir / "log.clf").string(), "-o", (dir / "log.stream").string()},
               dir / "log.stream", 4, 300, 5);
  fs::remove_all(dir);
}

TEST(Faults, SigkillDuringSweepMergeLeavesOldOrCompleteFiles) {
  const fs::path dir = TempDir("merge");
  std::ofstream(dir / "sweep.yaml") << "scenarios: [landmarks]\nalgorithms: [odometry]\nseeds: 4\nset: {duration_s: 12}\n";
  ASSERT_EQ(testing::RunSlambox(kBinary, "sweep " + (dir / "sweep.yaml").string() + " -j 2 -o " + (dir / "out").string())
                .code,
            0);
  KillAtRandom({"sweep", "--merge", (dir / "out").string()}, dir / "out", 4, 2000, 6);
  fs::remove_all(dir);
}

TEST(Faults, FullDiskGivesAClearErrorAndNoPartialFile) {
  if (geteuid() != 0) GTEST_SKIP() << "mounting a small tmpfs needs root";
  const fs::path mnt = TempDir("enospc");
  if (mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=64k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here: " << std::strerror(errno);
  std::ofstream(mnt / "s.stream") << "old";  // an old file the failed write must leave alone
  const auto r = testing::RunSlambox(kBinary, "simulate landmarks --set duration_s=20 -o " + (mnt / "s.stream").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("No space left on device"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find((mnt / "s.stream").string()), std::string::npos) << r.output;
  EXPECT_EQ(Read(mnt / "s.stream"), "old");
  const auto run = testing::RunSlambox(kBinary, "run landmarks --set duration_s=20 --algo odometry -o " + (mnt / "run").string());
  EXPECT_NE(run.code, 0);
  EXPECT_NE(run.output.find("No space left on device"), std::string::npos) << run.output;
  for (const auto& e : fs::recursive_directory_iterator(mnt)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << "temporary left: " << e.path();
    if (e.is_regular_file() && e.path().filename() != "s.stream") ExpectComplete(e.path());
  }
  umount2(mnt.c_str(), MNT_DETACH);
  fs::remove_all(mnt);
}

TEST(Faults, SecondSweepOnARunningSweepsFolderRefuses) {
  const fs::path dir = TempDir("lock");
  const fs::path sweep = dir / "sweep.yaml";
  std::ofstream(sweep) << "scenarios: [landmarks]\nalgorithms: [odometry]\nseeds: 2\nset: {duration_s: 8}\n";
  const std::string out = (dir / "out").string();
  fs::create_directories(out);
  fs::copy_file(sweep, fs::path(out) / "sweep.yaml");  // as a running sweep has written it
  {
    const SweepLock held(out, ".lock");  // as a running sweep holds it
    for (const std::string& args : {"sweep " + sweep.string() + " --resume --no-figures -o " + out,
                                    "sweep " + sweep.string() + " --no-figures -o " + out,
                                    "sweep --merge " + out + " --no-figures"}) {
      const auto start = std::chrono::steady_clock::now();
      const auto r = testing::RunSlambox(kBinary, args);
      EXPECT_NE(r.code, 0) << args;
      EXPECT_NE(r.output.find("another slambox sweep is running on this folder (pid " + std::to_string(getpid()) + ")"),
                std::string::npos)
          << r.output;
      EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
    }
    EXPECT_FALSE(fs::exists(fs::path(out) / "results.csv"));
  }
  {
    const SweepLock shard(out, ".lock.shard-1-of-2");  // as a running shard holds it
    const auto r = testing::RunSlambox(kBinary, "sweep --merge " + out + " --no-figures");
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.output.find(".lock.shard-1-of-2"), std::string::npos) << r.output;
    // Another shard of the same folder runs beside it (here: just takes its own lock).
    EXPECT_NO_THROW(SweepLock(out, ".lock.shard-0-of-2"));
  }
  // Released: the sweep runs; a real sweep holds the lock while it runs (seen from here).
  const pid_t pid = Spawn({"sweep", sweep.string(), "-j", "1", "--no-figures", "-o", out});
  bool seen = false;
  for (int i = 0; i < 200 && !seen; ++i) {
    const int fd = open((fs::path(out) / ".lock").c_str(), O_RDWR);
    if (fd >= 0) {
      struct flock q {};
      q.l_type = F_WRLCK;
      q.l_whence = SEEK_SET;
      seen = fcntl(fd, F_GETLK, &q) == 0 && q.l_type != F_UNLCK && q.l_pid == pid;
      close(fd);
    }
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(seen) << "the sweep did not hold " << out << "/.lock";
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_TRUE(fs::exists(fs::path(out) / "results.csv"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slambox
