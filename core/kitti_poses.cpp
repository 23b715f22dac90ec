#include "core/kitti_poses.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace slambox {

void WriteKittiPoses(const std::string& path, const std::vector<StampedPose>& poses) {
  WriteFileAtomic(path, [&](std::ostream& out) {
    char line[512];
    for (const auto& p : poses) {
      const double c = std::cos(p.pose.theta), s = std::sin(p.pose.theta);
      std::snprintf(line, sizeof line, "%.17g %.17g 0 %.17g %.17g %.17g 0 %.17g 0 0 1 0\n", c, -s, p.pose.x, s, c,
                    p.pose.y);
      out << line;
    }
  });
}

std::vector<StampedPose> ReadKittiPoses(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open the trajectory file", "check the path");
  std::vector<StampedPose> poses;
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    std::istringstream s(text);
    double r[12];
    for (double& x : r)
      if (!(s >> x))
        throw InputError(path, line_no, "expected 12 numbers (3 x 4 pose matrix, row-major), got: " + text,
                         "write one pose per line in KITTI format");
    std::string rest;
    if (s >> rest) throw InputError(path, line_no, "more than 12 numbers on the line", "write one 3 x 4 pose per line");
    for (double x : r)
      if (!std::isfinite(x)) throw InputError(path, line_no, "non-finite value", "remove or fix the pose");
    constexpr double kTol = 1e-6;
    if (std::abs(r[2]) > kTol || std::abs(r[6]) > kTol || std::abs(r[8]) > kTol || std::abs(r[9]) > kTol ||
        std::abs(r[10] - 1.0) > kTol || std::abs(r[11]) > kTol)
      throw InputError(path, line_no, "the pose leaves the x-y plane (rotation not about z, or z != 0)",
                       "slambox is 2D: give planar poses (KITTI's camera frame moves in x-z; rotate it to x-y first)");
    poses.push_back({static_cast<double>(poses.size()), SE2(r[3], r[7], std::atan2(r[4], r[0]))});
  }
  return poses;
}

TrajectoryFormat DetectTrajectoryFormat(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open the trajectory file", "check the path");
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    std::istringstream s(text);
    std::string field;
    int n = 0;
    while (s >> field) ++n;
    if (n == 8) return TrajectoryFormat::kTum;
    if (n == 12) return TrajectoryFormat::kKitti;
    throw InputError(path, line_no, "a trajectory line has " + std::to_string(n) + " fields",
                     "give TUM (8 numbers: t x y z qx qy qz qw) or KITTI (12 numbers: a 3 x 4 pose matrix)");
  }
  throw InputError(path, 0, "no pose in the file", "give a non-empty TUM or KITTI file");
}

}  // namespace slambox
