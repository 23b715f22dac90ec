#pragma once
// Test support for the pose graph: a synthetic multi-lap square trajectory with odometry
// and loop-closure edges (optionally noisy, fixed seed), and the public reference values.
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "slam/pose_graph.hpp"
#include "tests/support/public_data.hpp"

namespace slambox::testing {

struct SyntheticGraphOptions {
  int laps = 3;
  int poses_per_side = 5;
  double side_m = 4.0;
  double sigma_xy_m = 0.0;       ///< measurement noise, each edge
  double sigma_theta_rad = 0.0;
  std::uint64_t seed = 1;
};

struct SyntheticGraph {
  PoseGraph graph;         ///< poses = truth (callers perturb them)
  std::vector<SE2> truth;
};

/// Square path driven `laps` times (headings wrap past +-pi every lap); odometry edges
/// i -> i+1, loop closures from each pose of laps >= 1 to the same place in lap 0.
inline SyntheticGraph MakeSquareGraph(const SyntheticGraphOptions& o) {
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  SyntheticGraph s;
  const int per_lap = 4 * o.poses_per_side;
  const double step_m = o.side_m / o.poses_per_side;
  s.truth.push_back(SE2(0.0, 0.0, 0.0));
  for (int k = 1; k <= o.laps * per_lap; ++k) {
    const bool corner = k % o.poses_per_side == 0;
    s.truth.push_back(s.truth.back() * SE2(step_m, 0.0, corner ? M_PI / 2 : 0.0));
  }
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  if (o.sigma_xy_m > 0) information.topLeftCorner<2, 2>() /= o.sigma_xy_m * o.sigma_xy_m;
  if (o.sigma_theta_rad > 0) information(2, 2) /= o.sigma_theta_rad * o.sigma_theta_rad;
  if (o.sigma_xy_m == 0) information = Eigen::Vector3d(100.0, 100.0, 400.0).asDiagonal();
  auto add_edge = [&](int i, int j, bool loop) {
    const SE2 T = Between(s.truth[i], s.truth[j]);
    const SE2 noisy(T.x + o.sigma_xy_m * gauss(rng), T.y + o.sigma_xy_m * gauss(rng),
                    T.theta + o.sigma_theta_rad * gauss(rng));
    s.graph.edges.push_back({i, j, noisy, information, loop});
  };
  const int n = static_cast<int>(s.truth.size());
  for (int i = 0; i + 1 < n; ++i) add_edge(i, i + 1, false);
  for (int j = per_lap; j < n; ++j) add_edge(j % per_lap, j, true);
  s.graph.poses = s.truth;
  return s;
}

/// Perturbs every pose but the anchor by independent Gaussian noise (seeded).
inline std::vector<SE2> Perturbed(const std::vector<SE2>& poses, int anchor, double sigma_xy_m,
                                  double sigma_theta_rad, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<SE2> out = poses;
  for (size_t i = 0; i < out.size(); ++i) {
    if (static_cast<int>(i) == anchor) continue;
    out[i] = SE2(out[i].x + sigma_xy_m * gauss(rng), out[i].y + sigma_xy_m * gauss(rng),
                 out[i].theta + sigma_theta_rad * gauss(rng));
  }
  return out;
}

inline double MaxPositionError(const std::vector<SE2>& a, const std::vector<SE2>& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i].translation() - b[i].translation()).norm());
  return worst;
}

struct ReferenceValues {
  double chi2_init = 0.0;  ///< at the file's VERTEX guess, else the odometry chain
  double chi2_opt = 0.0;   ///< at an independent LM optimum
  std::string init_source;
};

/// refs/reference_values.tsv keyed by the graph's file name (e.g. "intel.g2o").
inline std::map<std::string, ReferenceValues> LoadReferenceValues(const std::string& source_dir) {
  std::map<std::string, ReferenceValues> refs;
  const std::string path = PublicDataFile(source_dir, "refs/reference_values.tsv");
  if (path.empty()) return refs;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("file\t", 0) == 0) continue;
    std::vector<std::string> cols;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, '\t');) cols.push_back(c);
    if (cols.size() < 8) continue;
    const std::string file = cols[0].substr(0, cols[0].find(' '));
    refs[file.substr(file.rfind('/') + 1)] = {std::stod(cols[6]), std::stod(cols[5]), cols[7]};
  }
  return refs;
}

}  // namespace slambox::testing
