// The entry point of slambox-render.so (app/render_library.hpp): the renderer's commands.
#include "app/render_library.hpp"
#include "render/figures_run.hpp"
#include "render/figures_sweep.hpp"
#include "render/run_pictures.hpp"

namespace {
void RunFigures(const std::string& dir) { slambox::render::RenderRunFigures(dir); }
int RunFrames(const std::string& dir) { return slambox::render::RenderRunFrames(dir); }
void RunPictures(const slambox::render::RunFolder& run, const std::string& dir) {
  slambox::render::RenderRunPictures(run, dir);
}
}  // namespace

extern "C" __attribute__((visibility("default"))) const slambox::RenderLibrary* slambox_render_library() {
  static const slambox::RenderLibrary library{slambox::kRenderLibraryAbi, &RunFigures, &RunFrames,
                                              &slambox::render::RenderSweepFigures, &slambox::render::WriteReport,
                                              &slambox::render::DetectFolder, &RunPictures};
  return &library;
}
