// The entry point of slambox-render.so (app/render_library.hpp): the renderer's commands.
#include "app/render_library.hpp"
#include "render/figures_run.hpp"
#include "render/figures_sweep.hpp"

namespace {
void RunFigures(const std::string& dir) { slambox::render::RenderRunFigures(dir); }
int RunFrames(const std::string& dir) { return slambox::render::RenderRunFrames(dir); }
}  // namespace

extern "C" __attribute__((visibility("default"))) const slambox::RenderLibrary* slambox_render_library() {
  static const slambox::RenderLibrary library{slambox::kRenderLibraryAbi, &RunFigures, &RunFrames,
                                              &slambox::render::RenderSweepFigures, &slambox::render::WriteReport,
                                              &slambox::render::DetectFolder};
  return &library;
}
