#pragma once
// The individual figures of a run folder; each returns false (and writes nothing) when
// the run lacks the data it needs. `stem` is the output path without extension.
#include <string>

#include "render/run_folder.hpp"

namespace slambox::render {

inline constexpr int kFigureWidthPx = 1200;

/// `extent_of` (default: run) fixes the region shown, so animation frames do not jump.
bool DrawTrajectoriesFigure(const RunFolder& run, const std::string& stem, const RunFolder* extent_of = nullptr);
bool DrawMapFigure(const RunFolder& run, size_t algo, const std::string& stem);
bool DrawUncertaintyFigure(const RunFolder& run, size_t algo, const std::string& stem);
bool DrawParticlesFigure(const RunFolder& run, size_t algo, const std::string& stem);
bool DrawPoseGraphFigure(const RunFolder& run, size_t algo, const std::string& stem);
bool DrawErrorFigure(const RunFolder& run, const std::string& stem);
bool DrawNeesFigure(const RunFolder& run, const std::string& stem);

}  // namespace slambox::render
