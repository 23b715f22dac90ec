#include "eval/evo_result.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

namespace slambox {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Evaluation Sample(AlignMode align) {
  GroundTruth gt;
  Estimate est;
  for (int i = 0; i < 40; ++i) {
    const double t = 0.1 * i;
    gt.trajectory.push_back({t, SE2(0.5 * i, 0.1 * i, 0.01 * i)});
    est.trajectory.push_back({t, SE2(0.5 * i + 0.02 * std::sin(i), 0.1 * i + 0.01 * i, 0.01 * i), Eigen::Matrix3d::Zero(), false});
  }
  EvalOptions o;
  o.align = align;
  return EvaluateEstimate(gt, est, o);
}

// Shape and data of a .npy entry (the layout NpyFloat64 writes; numpy's own check is below).
std::pair<std::string, std::vector<double>> ParseNpy(const std::string& npy) {
  const std::size_t len = static_cast<unsigned char>(npy[8]) | (static_cast<unsigned char>(npy[9]) << 8);
  const std::string header = npy.substr(10, len);
  const auto a = header.find("'shape': ") + 9;
  std::vector<double> data((npy.size() - 10 - len) / 8);
  if (!data.empty()) std::memcpy(data.data(), npy.data() + 10 + len, data.size() * 8);
  return {header.substr(a, header.find(')', a) - a + 1), data};
}

TEST(EvoResult, KeysAndArrayShapesOfEvoApe) {
  const Evaluation ev = Sample(AlignMode::kNone);
  std::map<std::string, std::string> entries;
  for (auto& e : EvoApeResultEntries(ev, AlignMode::kNone, {"gt", "est"})) entries[e.name] = e.bytes;
  for (const char* name : {"info.json", "stats.json", "error_array.npz", "timestamps.npz", "seconds_from_start.npz",
                           "distances_from_start.npz"})
    EXPECT_TRUE(entries.count(name)) << name;
  EXPECT_FALSE(entries.count("alignment_transformation_sim3.npz")) << "not aligned";
  const json info = json::parse(entries["info.json"]);
  EXPECT_EQ(info["title"], "APE w.r.t. translation part (m)\n(not aligned)");
  EXPECT_EQ(info["ref_name"], "gt");
  EXPECT_EQ(info["est_name"], "est");
  EXPECT_EQ(info["label"], "APE (m)");
  const json stats = json::parse(entries["stats.json"]);
  for (const char* k : {"rmse", "mean", "median", "std", "min", "max", "sse"}) EXPECT_TRUE(stats[k].is_number()) << k;
  EXPECT_DOUBLE_EQ(stats["rmse"].get<double>(), ev.metrics.ate.rmse);
  EXPECT_DOUBLE_EQ(stats["max"].get<double>(), ev.metrics.ate.max);
  const auto [shape, errors] = ParseNpy(entries["error_array.npz"]);
  EXPECT_EQ(shape, "(40,)");
  ASSERT_EQ(errors.size(), 40u);
  double sse = 0;
  for (int i = 0; i < 40; ++i) {
    EXPECT_EQ(errors[i], ev.series.ate_m[i]);
    sse += errors[i] * errors[i];
  }
  EXPECT_NEAR(stats["sse"].get<double>(), sse, 1e-12);
  const auto [ts_shape, ts] = ParseNpy(entries["timestamps.npz"]);
  EXPECT_EQ(ts_shape, "(40,)");
  EXPECT_EQ(ts[39], 3.9000000000000004);  // 0.1 * 39 as the trajectory holds it
  const auto seconds = ParseNpy(entries["seconds_from_start.npz"]).second;
  EXPECT_EQ(seconds.front(), 0.0);
  EXPECT_EQ(seconds.back(), ts.back() - ts.front());
}

TEST(EvoResult, AlignedResultCarriesTheTransformation) {
  const Evaluation ev = Sample(AlignMode::kSE2);
  std::map<std::string, std::string> entries;
  for (auto& e : EvoApeResultEntries(ev, AlignMode::kSE2, {})) entries[e.name] = e.bytes;
  EXPECT_EQ(json::parse(entries["info.json"])["title"], "APE w.r.t. translation part (m)\n(with SE(3) Umeyama alignment)");
  ASSERT_TRUE(entries.count("alignment_transformation_sim3.npz"));
  const auto [shape, m] = ParseNpy(entries["alignment_transformation_sim3.npz"]);
  EXPECT_EQ(shape, "(4, 4)");
  ASSERT_EQ(m.size(), 16u);
  EXPECT_NEAR(m[0] * m[0] + m[4] * m[4], 1.0, 1e-12);  // a rotation block
  EXPECT_EQ(m[15], 1.0);
}

// evo's own reader path (file_interface.load_res_file): zipfile + np.load of every *.npz.
TEST(EvoResult, NumpyLoadsTheArchiveAsEvoDoes) {
  // Debian's python3-numpy serves /usr/bin/python3 (a python3 earlier on PATH may lack it).
  std::string python;
  for (const char* candidate : {"/usr/bin/python3", "python3"})
    if (std::system((std::string(candidate) + " -c 'import numpy' > /dev/null 2>&1").c_str()) == 0) {
      python = candidate;
      break;
    }
  if (python.empty()) GTEST_SKIP() << "no python3 with numpy (Debian: python3-numpy)";
  const fs::path dir = fs::temp_directory_path() / ("slambox_evo_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Evaluation ev = Sample(AlignMode::kSE2);
  WriteEvoApeResult((dir / "r.zip").string(), ev, AlignMode::kSE2, {"gt", "est"});
  std::ofstream(dir / "load.py") << R"(import io, json, os, sys, zipfile
import numpy as np
with zipfile.ZipFile(sys.argv[1]) as archive:
    names = archive.namelist()
    assert {"error_array.npz", "info.json", "stats.json"} <= set(names), names
    out = {"info": json.loads(archive.read("info.json").decode("utf-8")),
           "stats": json.loads(archive.read("stats.json").decode("utf-8")), "arrays": {}}
    for n in names:
        if n.endswith(".npz"):
            with io.BytesIO(archive.read(n)) as f:
                a = np.load(f)
                out["arrays"][os.path.splitext(n)[0]] = {"shape": list(a.shape), "dtype": str(a.dtype),
                                                         "sum": float(a.sum())}
print(json.dumps(out))
)";
  const std::string cmd = python + " " + (dir / "load.py").string() + " " + (dir / "r.zip").string() + " > " +
                          (dir / "out.json").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const json out = json::parse(std::ifstream(dir / "out.json"));
  EXPECT_EQ(out["info"]["est_name"], "est");
  EXPECT_DOUBLE_EQ(out["stats"]["rmse"].get<double>(), ev.metrics.ate.rmse);
  for (const char* n : {"error_array", "timestamps", "seconds_from_start", "distances_from_start"}) {
    EXPECT_EQ(out["arrays"][n]["shape"], json::array({40})) << n;
    EXPECT_EQ(out["arrays"][n]["dtype"], "float64") << n;
  }
  EXPECT_EQ(out["arrays"]["alignment_transformation_sim3"]["shape"], json::array({4, 4}));
  double sum = 0;
  for (const double v : ev.series.ate_m) sum += v;
  EXPECT_NEAR(out["arrays"]["error_array"]["sum"].get<double>(), sum, 1e-12);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slambox
