#pragma once
// The sweep report's pictures of one run, drawn by the sweep worker from the run it holds
// in memory (no file read back, no re-simulation): DIR/pictures/trajectories.png (the
// world, ground truth and every module's path) and DIR/pictures/map_<algo>.png for each
// module that built a map (grid, LIDAR points or landmarks). Smaller than the run figures
// and PNG only, so a sweep pays little for them; a converted log (no world, no ground
// truth) gets the maps only. The report (render/report.cpp) embeds those of one
// representative seed per scenario (RepresentativeRun).
#include <string>
#include <vector>

#include "eval/results_table.hpp"
#include "render/run_folder.hpp"

namespace slambox::render {

inline constexpr const char* kPicturesDir = "pictures";

/// Writes the pictures of `run` under run_dir/pictures/; returns their stems relative to
/// run_dir ("pictures/trajectories", "pictures/map_icp-poseslam", ...), in drawing order.
std::vector<std::string> RenderRunPictures(const RunFolder& run, const std::string& run_dir);

/// The file-name-safe form of a module name, as the figures name their files.
std::string SafeFileName(const std::string& name);

/// Of the rows of one sweep cell (scenario and grid point, every module of each seed), the
/// run_id of the representative seed: each module's seeds are ranked by ATE RMSE (a failed
/// run or a missing ATE ranks last), each seed's ranks averaged over the modules, and the
/// seed with the median average rank taken (the lower middle of an even count; ties by
/// seed). Empty for no rows.
struct Representative {
  std::string run_id;
  std::uint64_t seed = 0;
  int seeds = 0;  ///< seeds in the cell
};
Representative RepresentativeRun(const std::vector<const ResultRow*>& rows);

}  // namespace slambox::render
