#pragma once
// Figures of a sweep folder (written by `slambox sweep`), into DIR/figures/.
#include <string>
#include <vector>

namespace slambox::render {

/// Writes sweep_dir/figures/{box_<metric>, vs_<key>, heatmap_<algo>}.{png,svg}: box plots
/// per module and scenario, the metric against each swept parameter (mean with the 95%
/// interval sweep.json's `interval` names), and a heatmap over the first two swept parameters. Throws InputError for a
/// missing or malformed sweep folder.
void RenderSweepFigures(const std::string& sweep_dir);
/// As RenderSweepFigures, returning the written stems relative to sweep_dir.
std::vector<std::string> RenderSweepFiguresListed(const std::string& sweep_dir);

}  // namespace slambox::render

namespace slambox {
// The app calls the entry points by their short names.
using render::RenderSweepFigures;
}  // namespace slambox
