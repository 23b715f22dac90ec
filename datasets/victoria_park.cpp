#include "datasets/victoria_park.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <vector>

#include "core/error.hpp"
#include "datasets/compressed_file.hpp"
#include "datasets/landmark_log.hpp"
#include "datasets/number_rows.hpp"

namespace slambox {

Stream ParseVictoriaPark(const std::string& text, const std::string& name, const VictoriaParkImportOptions& o) {
  if (!(o.pose_period_s > 0) || !(o.fov_deg > 0 && o.fov_deg <= 360))
    throw InputError(name, 0, "invalid import options (pose_period_s > 0, 0 < fov_deg <= 360)",
                     "check --pose-period-s / --fov-deg");
  std::map<int, std::pair<SE2, Eigen::Matrix3d>> odometry;  // end pose -> increment, covariance
  LandmarkLog log;
  int last_observed = -1;
  for (const NumberRow& row : ParseNumberRows(text, name, "fix or delete this line (format: datasets/victoria_park.hpp)")) {
    const std::vector<double>& v = row.values;
    const auto fail = [&](const std::string& problem) {
      throw InputError(name, row.line, problem, "fix or delete this line (format: datasets/victoria_park.hpp)");
    };
    if (v.size() != 12) fail("expected 12 fields, found " + std::to_string(v.size()));
    const auto index = [&](double x, const char* what) {
      if (x < 0 || x != std::floor(x) || x > 1e9) fail(std::string(what) + " must be a non-negative whole number");
      return static_cast<int>(x);
    };
    if (v[0] == 1) {
      const int i = index(v[1], "the start pose index"), j = index(v[2], "the end pose index");
      if (j != i + 1) fail("odometry must join consecutive poses (i, i + 1), got " + std::to_string(i) + " -> " + std::to_string(j));
      Eigen::Matrix3d P;
      P << v[6], v[7], v[8], v[7], v[9], v[10], v[8], v[10], v[11];
      if (!odometry.emplace(j, std::pair{SE2(v[3], v[4], v[5]), P}).second)
        fail("a second odometry row ends at pose " + std::to_string(j));
    } else if (v[0] == 0) {
      const int k = index(v[1], "the pose index"), f = index(v[2], "the feature index");
      if (!(std::hypot(v[3], v[4]) > 0)) fail("an observation at zero range");
      Eigen::Matrix2d P;
      P << v[5], v[6], v[6], v[7];
      log.sightings.push_back({k, f, Eigen::Vector2d(v[3], v[4]), P});
      last_observed = std::max(last_observed, k);
    } else {
      fail("the first field must be 1 (odometry) or 0 (observation)");
    }
  }
  if (odometry.empty()) throw InputError(name, 0, "no odometry row", "give VicPark_clean_data.txt (rows starting with 1 or 0)");
  const int last = odometry.rbegin()->first;
  for (int k = 1; k <= last; ++k)
    if (!odometry.count(k)) throw InputError(name, 0, "no odometry row ends at pose " + std::to_string(k), "the poses must form one chain 0, 1, 2, ...");
  if (last_observed > last)
    throw InputError(name, 0, "an observation names pose " + std::to_string(last_observed) + " beyond the last (" + std::to_string(last) + ")",
                     "check the pose indices");
  for (const auto& [end, step] : odometry) {  // the chain in pose order, whatever the rows' order
    log.increments.push_back(step.first);
    log.increment_covariances.push_back(step.second);
  }
  LandmarkLogOptions options{.pose_period_s = o.pose_period_s, .fov_deg = o.fov_deg, .odometry_alpha = o.odometry_alpha,
                             .description = "the Victoria Park data"};
  Stream s = AssembleLandmarkLog(log, name, options);
  return s;
}

Stream ReadVictoriaPark(const std::string& path, const VictoriaParkImportOptions& options) {
  return ParseVictoriaPark(ReadMaybeCompressedFile(path), path, options);
}

}  // namespace slambox
