// `slambox report DIR [--frames]`: figures (re-rendered when missing or older than the
// results) plus report.md and a self-contained report.html, for a run or a sweep folder.
#include <filesystem>
#include <iostream>

#include "app/commands.hpp"
#include "app/render_library.hpp"
#include "core/file_status.hpp"

namespace slambox {

namespace {
namespace fs = std::filesystem;

/// True when figures/ has no PNG or any PNG is older than the results file.
bool FiguresStale(const fs::path& dir, const fs::path& results) {
  const fs::path figs = dir / "figures";
  if (!PathExists(figs)) return true;
  bool any = false;
  const auto results_time = fs::last_write_time(results);
  for (const auto& e : fs::directory_iterator(figs)) {
    if (e.path().extension() != ".png") continue;
    any = true;
    if (fs::last_write_time(e.path()) < results_time) return true;
  }
  return !any;
}
}  // namespace

void AddReportCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("report", "Tables and figures (Markdown + self-contained HTML) for a run or sweep folder");
  auto dir = std::make_shared<std::string>();
  auto frames = std::make_shared<bool>(false);
  auto force = std::make_shared<bool>(false);
  cmd->add_option("DIR", *dir, "folder written by `slambox run -o DIR` or `slambox sweep -o DIR`")->required();
  cmd->add_flag("--frames", *frames, "also write animation frames DIR/frames/frame_NNNNN.png (runs only)");
  cmd->add_flag("--rerender", *force, "re-render the figures even when they are up to date");
  cmd->callback([dir, frames, force] {
    const fs::path d(*dir);
    const render::FolderKind kind = Render().detect_folder(*dir);  // InputError for anything else
    if (kind == render::FolderKind::kRun) {
      if (*force || FiguresStale(d, d / "metrics.json")) Render().run_figures(*dir);
      if (*frames) {
        const int n = Render().run_frames(*dir);
        std::cout << "wrote " << n << " frames to " << (d / "frames").string() << "\n";
      }
    } else {
      const fs::path results = d / "results.csv";
      if (*force || !PathExists(results) || FiguresStale(d, results)) Render().sweep_figures(*dir);
    }
    Render().write_report(*dir);
    std::cout << "wrote " << (d / "report.md").string() << " and " << (d / "report.html").string() << "\n";
  });
}

}  // namespace slambox
