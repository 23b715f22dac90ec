#include "core/tum.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/limits.hpp"

namespace slambox {

void WriteTum(const std::string& path, const std::vector<StampedPose>& poses) {
  WriteFileAtomic(path, [&](std::ostream& out) {
    char line[256];
    for (const auto& p : poses) {
      // yaw-only quaternion: (0, 0, sin(theta/2), cos(theta/2)); %.17g round-trips doubles.
      std::snprintf(line, sizeof line, "%.9f %.17g %.17g 0 0 0 %.17g %.17g\n", p.t_s, p.pose.x, p.pose.y,
                    std::sin(p.pose.theta / 2), std::cos(p.pose.theta / 2));
      out << line;
    }
  });
}

std::vector<StampedPose> ReadTum(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the trajectory file", "check the path");
  std::ostringstream all;
  all << in.rdbuf();
  return ParseTum(all.str(), path);
}

std::vector<StampedPose> ParseTum(const std::string& content, const std::string& path) {
  std::vector<StampedPose> poses;
  std::istringstream in(content);
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    limits::CheckLineLength(path, line_no, text.size());
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    std::istringstream s(text);
    double v[8];
    for (double& x : v)
      if (!(s >> x))
        throw InputError(path, line_no, "expected 8 numbers 't x y z qx qy qz qw', got: " + text,
                         "write one pose per line in TUM format");
    for (double x : v)
      if (!std::isfinite(x)) throw InputError(path, line_no, "non-finite value", "remove or fix the pose");
    const double qn = std::sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]);
    if (qn < 1e-9) throw InputError(path, line_no, "zero quaternion", "give a unit quaternion qx qy qz qw");
    const double qx = v[4] / qn, qy = v[5] / qn, qz = v[6] / qn, qw = v[7] / qn;
    const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
    if (!poses.empty() && v[0] <= poses.back().t_s)
      throw InputError(path, line_no, "timestamps must increase", "sort the file by time and remove duplicates");
    poses.push_back({v[0], SE2(v[1], v[2], yaw)});
  }
  return poses;
}

}  // namespace slambox
