#pragma once
// Figures and reports come from lib/slambox/slambox-render.so, loaded at the first figure.
// The renderer links OSMesa and through it LLVM (~50 MiB resident, tens of ms to load):
// commands that draw nothing (`scenarios`, `simulate`, `run --no-figures`, `sweep
// --no-figures`) never load it; a sweep with figures loads it before its workers fork, so
// they draw their run's pictures without loading it again. app/render_library_entry.cpp is the library's side.
#include <string>

#include "render/report.hpp"
#include "render/run_folder.hpp"

namespace slambox {

/// Bumped whenever a member changes; the loader refuses a library with another value.
inline constexpr int kRenderLibraryAbi = 2;

struct RenderLibrary {
  int abi = kRenderLibraryAbi;
  void (*run_figures)(const std::string& run_dir);
  int (*run_frames)(const std::string& run_dir);  ///< frames at the renderer's default count
  void (*sweep_figures)(const std::string& sweep_dir);
  void (*write_report)(const std::string& dir);
  render::FolderKind (*detect_folder)(const std::string& dir);  ///< throws InputError
  /// The sweep report's pictures of a run held in memory (render/run_pictures.hpp).
  void (*run_pictures)(const render::RunFolder& run, const std::string& run_dir);
};

/// Loads the library once (lib/slambox/ beside the executable's folder). Throws
/// std::runtime_error naming the file when it is missing or does not load.
const RenderLibrary& Render();

}  // namespace slambox
