#pragma once
// Figures of one run folder (written by `slambox run`), into DIR/figures/ as .png + .svg.
#include <string>
#include <vector>

namespace slambox::render {

/// Writes run_dir/figures/{trajectories, error_distance, nees, map_<algo>,
/// uncertainty_<algo>, particles_<algo>, pose_graph_<algo>}.{png,svg}; figures whose data
/// the run lacks are skipped. Throws InputError for a missing or malformed run folder.
void RenderRunFigures(const std::string& run_dir);

/// As RenderRunFigures, returning the written figure stems (relative to run_dir, e.g.
/// "figures/trajectories") in drawing order.
std::vector<std::string> RenderRunFiguresListed(const std::string& run_dir);

/// Numbered animation frames run_dir/frames/frame_00000.png ...: the paths growing over
/// time with the robot's true pose marked. Returns the number of frames written.
int RenderRunFrames(const std::string& run_dir, int frame_count = 120);

}  // namespace slambox::render

namespace slambox {
// The app calls the entry points by their short names.
using render::RenderRunFigures;
}  // namespace slambox
