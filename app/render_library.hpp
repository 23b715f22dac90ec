#pragma once
// Figures and reports come from lib/slambox/slambox-render.so, loaded at the first figure.
// The renderer links OSMesa and through it LLVM (~50 MiB resident, tens of ms to load):
// commands that draw nothing (`scenarios`, `simulate`, `run --no-figures`, sweep workers)
// never load it. app/render_library_entry.cpp is the library's side.
#include <string>

#include "render/report.hpp"

namespace slambox {

/// Bumped whenever a member changes; the loader refuses a library with another value.
inline constexpr int kRenderLibraryAbi = 1;

struct RenderLibrary {
  int abi = kRenderLibraryAbi;
  void (*run_figures)(const std::string& run_dir);
  int (*run_frames)(const std::string& run_dir);  ///< frames at the renderer's default count
  void (*sweep_figures)(const std::string& sweep_dir);
  void (*write_report)(const std::string& dir);
  render::FolderKind (*detect_folder)(const std::string& dir);  ///< throws InputError
};

/// Loads the library once (lib/slambox/ beside the executable's folder). Throws
/// std::runtime_error naming the file when it is missing or does not load.
const RenderLibrary& Render();

}  // namespace slambox
