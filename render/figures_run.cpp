#include "render/figures_run.hpp"

#include <filesystem>

#include "render/figures_run_parts.hpp"
#include "render/run_pictures.hpp"

namespace slambox::render {

namespace fs = std::filesystem;

std::vector<std::string> RenderRunFiguresListed(const std::string& run_dir) {
  const RunFolder run = ReadRunFolder(run_dir);
  fs::create_directories(fs::path(run_dir) / "figures");
  std::vector<std::string> written;
  auto emit = [&](const std::string& name, auto&& draw) {
    const std::string rel = "figures/" + name;
    if (draw((fs::path(run_dir) / rel).string())) written.push_back(rel);
  };
  emit("trajectories", [&](const std::string& s) { return DrawTrajectoriesFigure(run, s); });
  emit("error_distance", [&](const std::string& s) { return DrawErrorFigure(run, s); });
  emit("nees", [&](const std::string& s) { return DrawNeesFigure(run, s); });
  for (size_t i = 0; i < run.algorithms.size(); ++i) {
    const std::string n = SafeFileName(run.algorithms[i].name);
    emit("map_" + n, [&](const std::string& s) { return DrawMapFigure(run, i, s); });
    emit("uncertainty_" + n, [&](const std::string& s) { return DrawUncertaintyFigure(run, i, s); });
    emit("particles_" + n, [&](const std::string& s) { return DrawParticlesFigure(run, i, s); });
    emit("pose_graph_" + n, [&](const std::string& s) { return DrawPoseGraphFigure(run, i, s); });
  }
  return written;
}

void RenderRunFigures(const std::string& run_dir) { RenderRunFiguresListed(run_dir); }

}  // namespace slambox::render
