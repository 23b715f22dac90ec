#pragma once
// ROS occupancy map files, as ROS map_server and nav2's map_io read and write them:
//   map.yaml: image (relative to the YAML file unless absolute), resolution [m/cell],
//             origin [x, y, yaw] (pose of the lower-left pixel), negate (0|1),
//             occupied_thresh, free_thresh, mode (trinary | scale | raw; default trinary)
//   image:    8-bit (or 16-bit) PGM, P5 or P2; or PNG. Its top row is the grid's
//             highest-y row.
// Reading (nav2 map_io loadMapFromFile): shade = pixel / max (mean of the colour
// channels, plus alpha in trinary mode when the image has one), occ = negate ? shade :
// 1 - shade; trinary: occ > occupied_thresh -> 100, occ < free_thresh -> 0, else -1.
// Writing (nav2 map_saver, trinary): cell < 0 -> 205, cell <= rint(100 free_thresh) -> 254,
// cell >= rint(100 occupied_thresh) -> 0, else 205. With the thresholds written (0.65,
// 0.196, as ROS map_saver writes) a grid of {-1, 0, 100} round-trips bit-exactly; other
// values are quantized to those three.
#include <functional>
#include <string>

#include "core/estimate.hpp"

namespace slambox {

enum class RosMapMode { kTrinary, kScale, kRaw };

struct RosMapWriteOptions {
  double occupied_thresh = 0.65;  ///< occ above this reads back as occupied
  double free_thresh = 0.196;     ///< occ below this reads back as free (ROS map_saver's value)
};

/// Writes `yaml_path` and the image beside it (same stem, `.pgm`), each atomically, the
/// image first. Throws std::runtime_error on I/O failure; asserts a non-empty grid.
void WriteRosMap(const std::string& yaml_path, const OccupancyGrid& grid, const RosMapWriteOptions& options = {});

/// Reads a map.yaml and its image into a grid (origin = the lower-left pixel's corner).
/// Throws InputError naming the file and line for a missing or malformed key, thresholds
/// outside 0 <= free < occupied <= 1, a non-zero origin yaw, a missing or malformed image.
/// Keys other than the ones above are ignored (ROS tools add their own).
OccupancyGrid ReadRosMap(const std::string& yaml_path);

/// A file's bytes by path; throws InputError naming the path when there is no such file.
using MapFileReader = std::function<std::string(const std::string& path)>;
/// ReadRosMap through `read` for the YAML and the image (e.g. files embedded in the
/// binary); the image path is relative to the YAML's folder unless absolute.
OccupancyGrid ReadRosMap(const std::string& yaml_path, const MapFileReader& read);

}  // namespace slambox
