#pragma once
// TUM trajectory files (`t x y z qx qy qz qw`, readable by evo). 2D poses are written with
// z = 0 and a yaw-only quaternion; reading takes yaw from the quaternion.
#include <string>
#include <vector>

#include "core/stream.hpp"

namespace slambox {

void WriteTum(const std::string& path, const std::vector<StampedPose>& poses);  ///< atomic
/// Throws InputError naming the file and line for a malformed line, a non-finite value or
/// timestamps that are not increasing. Lines starting with '#' and blank lines are skipped.
std::vector<StampedPose> ReadTum(const std::string& path);
/// ReadTum of the file's text; `path` is used in error messages.
std::vector<StampedPose> ParseTum(const std::string& text, const std::string& path);

}  // namespace slambox
