#pragma once
// The individual figures of a run folder; each returns false (and writes nothing) when
// the run lacks the data it needs. `stem` is the output path without extension.
#include <string>

#include "render/run_folder.hpp"

namespace slambox::render {

inline constexpr int kFigureWidthPx = 1200;

/// How a world-frame figure is written: the run figures' size with an SVG beside the PNG,
/// or smaller and PNG only (the sweep report's pictures, drawn by every sweep worker).
struct FigureOutput {
  int width_px = kFigureWidthPx;
  int supersample = 3;  ///< samples per pixel and axis (anti-aliasing)
  bool svg = true;
};

/// " — scenario, seed N" for a simulated run; " — log" for a converted log (no ground
/// truth: a seed means nothing there); "" without a scenario name.
std::string RunTitleSuffix(const RunFolder& run);

/// For animation frames: `extent_of` fixes the region shown (so frames do not jump) and
/// `now_s` >= 0 titles the frame with its time and labels the path ends "now".
bool DrawTrajectoriesFigure(const RunFolder& run, const std::string& stem, const RunFolder* extent_of = nullptr,
                            double now_s = -1.0, const FigureOutput& out = {});
bool DrawMapFigure(const RunFolder& run, size_t algo, const std::string& stem, const FigureOutput& out = {});
bool DrawUncertaintyFigure(const RunFolder& run, size_t algo, const std::string& stem);
bool DrawParticlesFigure(const RunFolder& run, size_t algo, const std::string& stem);
bool DrawPoseGraphFigure(const RunFolder& run, size_t algo, const std::string& stem);
bool DrawErrorFigure(const RunFolder& run, const std::string& stem);
bool DrawNeesFigure(const RunFolder& run, const std::string& stem);

}  // namespace slambox::render
