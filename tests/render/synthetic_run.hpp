#pragma once
// Test support: a synthetic run folder in the layout `slambox run` writes (DESIGN.md),
// built without the simulator or any SLAM module: a robot drives two laps around a room
// with posts and a mover; "odometry" drifts, "ekf-slam" has pose and landmark
// covariances, "icp-poseslam" has map points, a grid and a pose graph with accepted and
// rejected loop closures, "fastslam2" has particle snapshots. Deterministic per seed.
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/json_io.hpp"
#include "core/tum.hpp"

namespace slambox::testing {

inline World SyntheticWorld() {
  World w;
  const std::vector<Eigen::Vector2d> room{{0, 0}, {20, 0}, {20, 10}, {0, 10}};
  for (int i = 0; i < 4; ++i) w.wall_segments.push_back({room[i], room[(i + 1) % 4]});
  w.wall_segments.push_back({{6, 5}, {14, 5}});  // a central wall
  w.wall_circles.push_back({{10, 7.5}, 0.3});
  for (int i = 0; i < 6; ++i) w.landmarks.push_back({i, {3.0 + 3.0 * i, i % 2 ? 3.5 : 6.5}, 0.1});
  MoverTrack m;
  m.path = {{4, 1}, {16, 1}};
  m.radius_m = 0.3;
  w.movers.push_back(m);
  return w;
}

inline void WriteSyntheticRun(const std::string& dir, std::uint64_t seed = 7, bool with_series = true) {
  namespace fs = std::filesystem;
  using nlohmann::json;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  const World world = SyntheticWorld();
  // Ground truth: two laps of the rectangle (2,2)-(18,8) at 1 m/s, 10 Hz.
  const std::vector<Eigen::Vector2d> corners{{2, 2}, {18, 2}, {18, 8}, {2, 8}};
  std::vector<StampedPose> gt;
  double t = 0.0;
  for (int lap = 0; lap < 2; ++lap)
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d a = corners[k], b = corners[(k + 1) % 4];
      const double len = (b - a).norm(), heading = std::atan2(b.y() - a.y(), b.x() - a.x());
      for (double s = 0.0; s < len - 1e-9; s += 0.1, t += 0.1)
        gt.push_back({t, SE2(a.x() + (b - a).x() * s / len, a.y() + (b - a).y() * s / len, heading)});
    }
  const size_t n = gt.size();
  auto lap_fraction = [&](size_t i) { return static_cast<double>(i) / n; };

  std::vector<StampedPose> odo, ekf;
  Estimate odo_est, ekf_est, icp_est, fs_est;
  for (size_t i = 0; i < n; ++i) {
    const double f = lap_fraction(i);
    // Odometry: a slow heading drift bends the path; covariance grows linearly.
    const SE2 drift(0.8 * f * f * 10, -0.5 * f * 10 * f, 0.0);
    const SE2 po(gt[i].pose.x + drift.x, gt[i].pose.y + drift.y, gt[i].pose.theta + 0.05 * f);
    odo.push_back({gt[i].t_s, po});
    PoseEstimate pe{gt[i].t_s, po, Eigen::Matrix3d::Identity() * (0.002 + 0.4 * f), true};
    odo_est.trajectory.push_back(pe);
    // EKF: small error; uncertainty grows during the first lap, collapses at loop closure.
    const double s = f < 0.5 ? 0.01 + 0.3 * f : 0.03;
    const SE2 pk(gt[i].pose.x + s * 0.3 * n01(rng), gt[i].pose.y + s * 0.3 * n01(rng), gt[i].pose.theta);
    ekf.push_back({gt[i].t_s, pk});
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    cov(0, 0) = s * s * 1.5;
    cov(1, 1) = s * s * 0.6;
    cov(0, 1) = cov(1, 0) = 0.3 * s * s;
    cov(2, 2) = 0.001;
    ekf_est.trajectory.push_back({gt[i].t_s, pk, cov, true});
  }
  for (const auto& l : world.landmarks) {
    Eigen::Matrix2d c;
    c << 0.02, 0.008, 0.008, 0.01;
    ekf_est.landmarks.push_back({l.id, l.position + Eigen::Vector2d(0.08 * n01(rng), 0.08 * n01(rng)), c, true});
  }
  // ICP pose-SLAM: nodes every 1 m, edges along the path, loop closures lap 1 <-> lap 2.
  for (size_t i = 0; i < n; i += 10) {
    icp_est.pose_graph.node_t_s.push_back(gt[i].t_s);
    icp_est.pose_graph.nodes.push_back(ekf[i].pose);
    icp_est.trajectory.push_back({gt[i].t_s, ekf[i].pose, Eigen::Matrix3d::Zero(), false});
  }
  const int nodes = static_cast<int>(icp_est.pose_graph.nodes.size());
  for (int i = 0; i + 1 < nodes; ++i) icp_est.pose_graph.edges.push_back({i, i + 1, false, true});
  for (int i = 0; i < nodes / 2; i += 4) icp_est.pose_graph.edges.push_back({i, i + nodes / 2, true, true});
  icp_est.pose_graph.edges.push_back({3, nodes - 20, true, false});
  icp_est.pose_graph.edges.push_back({30, 60, true, false});
  for (const auto& s : world.wall_segments)
    for (double u = 0.0; u <= 1.0; u += 0.004)
      icp_est.map_points.push_back(s.a + u * (s.b - s.a) + Eigen::Vector2d(0.02 * n01(rng), 0.02 * n01(rng)));
  OccupancyGrid grid;
  grid.origin_m = {-0.5, -0.5};
  grid.resolution_m = 0.1;
  grid.width = 210;
  grid.height = 110;
  grid.cells.assign(static_cast<size_t>(grid.width) * grid.height, -1);
  for (int iy = 5; iy < 105; ++iy)
    for (int ix = 5; ix < 205; ++ix) grid.cells[iy * grid.width + ix] = 0;
  for (const auto& p : icp_est.map_points) {
    const int ix = static_cast<int>((p.x() - grid.origin_m.x()) / 0.1), iy = static_cast<int>((p.y() - grid.origin_m.y()) / 0.1);
    if (ix >= 0 && iy >= 0 && ix < grid.width && iy < grid.height) grid.cells[iy * grid.width + ix] = 100;
  }
  icp_est.grid = grid;
  // FastSLAM: particle clouds at four steps, spread growing with time.
  fs_est.trajectory = ekf_est.trajectory;
  for (size_t k : {n / 8, 3 * n / 8, 5 * n / 8, 7 * n / 8}) {
    ParticleSnapshot snap;
    snap.t_s = gt[k].t_s;
    const double spread = 0.05 + 0.3 * lap_fraction(k);
    for (int p = 0; p < 60; ++p) {
      snap.poses.push_back(SE2(gt[k].pose.x + spread * n01(rng), gt[k].pose.y + spread * n01(rng), gt[k].pose.theta + 0.1 * n01(rng)));
      snap.weights.push_back(1.0 / 60);
    }
    fs_est.particles.push_back(snap);
  }

  fs::create_directories(fs::path(dir) / "estimates");
  fs::create_directories(fs::path(dir) / "series");
  WriteTum(dir + "/groundtruth.tum", gt);
  WriteFileAtomic(dir + "/world.json", json{{"scenario", "synthetic"}, {"seed", seed}, {"duration_s", t}, {"world", ToJson(world)}}.dump());
  const std::vector<std::pair<std::string, const Estimate*>> algos{
      {"ekf-slam", &ekf_est}, {"fastslam2", &fs_est}, {"icp-poseslam", &icp_est}, {"odometry", &odo_est}};
  json metrics{{"slambox_version", "test"}, {"scenario", "synthetic"}, {"seed", seed}, {"duration_s", t}, {"distance_m", 0.1 * n}};
  for (const auto& [name, est] : algos) {
    std::vector<StampedPose> traj;
    for (const auto& p : est->trajectory) traj.push_back({p.t_s, p.pose});
    WriteTum(dir + "/" + name + ".tum", traj);
    WriteFileAtomic(dir + "/estimates/" + name + ".json", ToJson(*est).dump());
    metrics["algorithms"][name] = {{"ate_rmse_m", name == "odometry" ? 2.1 : 0.05}, {"rpe_trans_rmse_m", 0.01},
                                   {"anees", name == "odometry" ? nullptr : json(3.2)}, {"landmark_rmse_m", nullptr},
                                   {"status", "ok"}};
    metrics["modules"][name] = {{"baseline", name == "odometry"}};  // as `slambox run` writes it (ModuleInfo)
    if (!with_series) continue;
    json ser{{"t_s", json::array()}, {"distance_m", json::array()}, {"ate_m", json::array()},
             {"heading_error_deg", json::array()}, {"nees", json::array()}, {"nees_band_95", {2.2, 3.9}}};
    json rpe{{"distance_m", json::array()}, {"trans_m", json::array()}, {"rot_deg", json::array()}};
    for (size_t i = 0; i < traj.size(); ++i) {
      const size_t g = std::min(n - 1, static_cast<size_t>(std::lround(traj[i].t_s / 0.1)));
      ser["t_s"].push_back(traj[i].t_s);
      ser["distance_m"].push_back(0.1 * g);
      ser["ate_m"].push_back((traj[i].pose.translation() - gt[g].pose.translation()).norm());
      ser["heading_error_deg"].push_back(0.0);
      if (name == "odometry") ser["nees"].push_back(nullptr);
      else ser["nees"].push_back(3.0 * std::exp(0.5 * n01(rng)) * (name == "fastslam2" ? 4.0 : 1.0));
      if (i % 10 == 0 && g >= 10) {
        rpe["distance_m"].push_back(0.1 * g);
        rpe["trans_m"].push_back(std::abs(0.01 + 0.005 * n01(rng)) * (name == "odometry" ? 3 : 1));
        rpe["rot_deg"].push_back(0.1);
      }
    }
    ser["rpe"] = rpe;
    WriteFileAtomic(dir + "/series/" + name + ".json", ser.dump());
  }
  WriteFileAtomic(dir + "/metrics.json", metrics.dump(2));
}

}  // namespace slambox::testing
