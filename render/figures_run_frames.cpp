// Animation frames for teaching: the trajectories figure with every path cut at time t,
// for evenly spaced t over the run.
#include <cstdio>
#include <filesystem>

#include "render/figures_run.hpp"
#include "render/figures_run_parts.hpp"

namespace slambox::render {

namespace {
std::vector<StampedPose> Until(const std::vector<StampedPose>& poses, double t_s) {
  std::vector<StampedPose> out;
  for (const auto& p : poses)
    if (p.t_s <= t_s) out.push_back(p);
  return out;
}
}  // namespace

int RenderRunFrames(const std::string& run_dir, int frame_count) {
  const RunFolder run = ReadRunFolder(run_dir);
  if (run.groundtruth.size() < 2 || frame_count < 1) return 0;
  const std::filesystem::path dir = std::filesystem::path(run_dir) / "frames";
  std::filesystem::create_directories(dir);
  const double t0 = run.groundtruth.front().t_s, t1 = run.groundtruth.back().t_s;
  int written = 0;
  for (int k = 0; k < frame_count; ++k) {
    const double t = t0 + (t1 - t0) * (k + 1) / frame_count;
    RunFolder cut = run;
    cut.groundtruth = Until(run.groundtruth, t);
    for (auto& a : cut.algorithms) a.trajectory = Until(a.trajectory, t);
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d", k);
    written += DrawTrajectoriesFigure(cut, (dir / name).string(), /*full_extent=*/&run);
  }
  return written;
}

}  // namespace slambox::render
