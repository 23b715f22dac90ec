#include "datasets/victoria_park.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "datasets/compressed_file.hpp"
#include "datasets/odometry_noise_fit.hpp"

namespace slambox {

namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
  return v[mid];
}

}  // namespace

Stream ParseVictoriaPark(const std::string& text, const std::string& name, const VictoriaParkImportOptions& o) {
  if (!(o.pose_period_s > 0) || !(o.fov_deg > 0 && o.fov_deg <= 360))
    throw InputError(name, 0, "invalid import options (pose_period_s > 0, 0 < fov_deg <= 360)",
                     "check --pose-period-s / --fov-deg");
  std::map<int, SE2> odometry;                                // end pose -> increment
  std::vector<SE2> increments;
  std::vector<Eigen::Matrix3d> increment_covariances;
  std::map<int, std::vector<LandmarkObservation>> observed;  // pose -> observations
  std::vector<double> sigma_range, sigma_bearing;
  double range_max = 0.0;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    limits::CheckLineLength(name, line_number, line.size());
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    std::istringstream fields(line);
    std::vector<double> v;
    std::string token;
    while (fields >> token) {
      char* end = nullptr;
      const double x = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(x))
        throw InputError(name, line_number, "'" + token + "' is not a finite number",
                         "fix or delete this line (format: datasets/victoria_park.hpp)");
      v.push_back(x);
    }
    const auto fail = [&](const std::string& problem) {
      throw InputError(name, line_number, problem, "fix or delete this line (format: datasets/victoria_park.hpp)");
    };
    if (v.size() != 12) fail("expected 12 fields, found " + std::to_string(v.size()));
    const auto index = [&](double x, const char* what) {
      if (x < 0 || x != std::floor(x) || x > 1e9) fail(std::string(what) + " must be a non-negative whole number");
      return static_cast<int>(x);
    };
    if (v[0] == 1) {
      const int i = index(v[1], "the start pose index"), j = index(v[2], "the end pose index");
      if (j != i + 1) fail("odometry must join consecutive poses (i, i + 1), got " + std::to_string(i) + " -> " + std::to_string(j));
      if (!odometry.emplace(j, SE2(v[3], v[4], v[5])).second) fail("a second odometry row ends at pose " + std::to_string(j));
      increments.push_back(SE2(v[3], v[4], v[5]));
      Eigen::Matrix3d P;
      P << v[6], v[7], v[8], v[7], v[9], v[10], v[8], v[10], v[11];
      increment_covariances.push_back(P);
    } else if (v[0] == 0) {
      const int k = index(v[1], "the pose index"), f = index(v[2], "the feature index");
      const double x = v[3], y = v[4], r = std::hypot(x, y);
      if (!(r > 0)) fail("an observation at zero range");
      observed[k].push_back({r, std::atan2(y, x), f});
      range_max = std::max(range_max, r);
      // Polar covariance J P J^T with J = d(r, b)/d(x, y) = [[x, y] / r; [-y, x] / r^2].
      Eigen::Matrix2d P;
      P << v[5], v[6], v[6], v[7];
      Eigen::Matrix2d J;
      J << x / r, y / r, -y / (r * r), x / (r * r);
      const Eigen::Matrix2d polar = J * P * J.transpose();
      sigma_range.push_back(std::sqrt(std::max(0.0, polar(0, 0))));
      sigma_bearing.push_back(std::sqrt(std::max(0.0, polar(1, 1))));
    } else {
      fail("the first field must be 1 (odometry) or 0 (observation)");
    }
  }
  if (odometry.empty()) throw InputError(name, 0, "no odometry row", "give VicPark_clean_data.txt (rows starting with 1 or 0)");
  const int last = odometry.rbegin()->first;
  for (int k = 1; k <= last; ++k)
    if (!odometry.count(k)) throw InputError(name, 0, "no odometry row ends at pose " + std::to_string(k), "the poses must form one chain 0, 1, 2, ...");
  if (!observed.empty() && observed.rbegin()->first > last)
    throw InputError(name, 0, "an observation names pose " + std::to_string(observed.rbegin()->first) + " beyond the last (" + std::to_string(last) + ")",
                     "check the pose indices");

  Stream s;
  s.header.scenario_name = std::filesystem::path(name).filename().string();
  s.header.scenario_yaml = "# converted from the Victoria Park data " + s.header.scenario_name + " (no ground truth)\n";
  s.header.dt_s = o.pose_period_s;
  for (int k = 0; k <= last; ++k) {
    const double t = k * o.pose_period_s;
    if (k > 0) s.events.push_back(OdometryEvent{t, odometry.at(k)});
    if (auto it = observed.find(k); it != observed.end()) s.events.push_back(LandmarkEvent{t, it->second});
  }
  s.header.duration_s = last * o.pose_period_s;
  OdometryConfig odo;
  odo.rate_hz = 1.0 / o.pose_period_s;
  odo.alpha = o.odometry_alpha ? *o.odometry_alpha : FitOdometryAlpha(increments, increment_covariances).alpha;
  LandmarkSensorConfig lm;
  lm.rate_hz = 1.0 / o.pose_period_s;
  lm.range_max_m = std::ceil(range_max);
  lm.fov_deg = o.fov_deg;
  lm.sigma_range_m = Median(sigma_range);
  lm.sigma_bearing_deg = Median(sigma_bearing) * 180.0 / M_PI;
  lm.known_ids = true;
  s.header.sensors.odometry = odo;
  s.header.sensors.landmarks = lm;
  return s;
}

Stream ReadVictoriaPark(const std::string& path, const VictoriaParkImportOptions& options) {
  return ParseVictoriaPark(ReadMaybeCompressedFile(path), path, options);
}

}  // namespace slambox
