#include "datasets/islsjf_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "datasets/compressed_file.hpp"
#include "datasets/landmark_log.hpp"
#include "datasets/number_rows.hpp"

namespace slambox {

namespace {

constexpr const char* kFormat = "fix or delete this line (format: datasets/islsjf_simulation.hpp)";

// `name = 0.3`, `name = 0.02;`, `name = (4*pi/180);` and trailing comments, per line.
std::map<std::string, double> ReadParameters(const std::string& path) {
  std::map<std::string, double> values;
  std::istringstream in(ReadMaybeCompressedFile(path));
  static const std::regex kAssignment(
      R"(^\s*([A-Za-z_]\w*)\s*=\s*\(?\s*([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(\*\s*pi\s*/\s*([0-9]*\.?[0-9]+))?\s*\)?.*$)");
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF files
    std::smatch m;
    if (!std::regex_match(line, m, kAssignment)) continue;
    double v = std::strtod(m[2].str().c_str(), nullptr);
    if (m[3].matched) {
      const double divisor = std::strtod(m[4].str().c_str(), nullptr);
      if (!(divisor > 0)) throw InputError(path, line_number, "division by zero", "write e.g. (4*pi/180)");
      v = v * M_PI / divisor;
    }
    values[m[1].str()] = v;
  }
  return values;
}

// Every number of a file in order, whatever its layout (a column or a MATLAB row vector).
std::vector<double> ReadSeries(const std::string& path) {
  std::vector<double> series;
  for (const NumberRow& row : ParseNumberRows(ReadMaybeCompressedFile(path), path, kFormat))
    series.insert(series.end(), row.values.begin(), row.values.end());
  return series;
}

// The option when given, else parameters.txt's `key`, checked > 0 (>= 0 for noise).
double Setting(const std::optional<double>& given, const std::map<std::string, double>& file, const char* key,
               const std::string& parameters_path, const char* option, bool zero_ok, double file_scale = 1.0) {
  double v = 0.0;
  if (given) {
    v = *given;
  } else {
    const auto it = file.find(key);
    if (it == file.end())
      throw InputError(parameters_path, 0, std::string("no '") + key + " = ...' line",
                       std::string("add it, or give ") + option);
    v = it->second * file_scale;
  }
  if (!std::isfinite(v) || v < 0 || (v == 0 && !zero_ok))
    throw InputError(given ? option : parameters_path, 0, std::string(key) + " must be a finite number " + (zero_ok ? ">= 0" : "> 0"),
                     std::string("give ") + option);
  return v;
}

}  // namespace

UnicycleStep IslsjfStep(double v, double w, double dt, double sigma_v, double sigma_w) {
  const double c = std::cos(w * dt), s = std::sin(w * dt);
  Eigen::Matrix<double, 3, 2> J;  // d(step)/d(v, w)
  J << dt * c, -v * dt * dt * s,
       dt * s, v * dt * dt * c,
       0.0, dt;
  return {SE2(v * dt * c, v * dt * s, w * dt),
          J * Eigen::Vector2d(sigma_v * sigma_v, sigma_w * sigma_w).asDiagonal() * J.transpose()};
}

Stream ReadIslsjfSimulation(const std::string& dir, const IslsjfSimulationOptions& o, IslsjfSimulationReport* report) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(dir))
    throw InputError(dir, 0, "not a directory", "give the folder that holds sensor_data.txt, store_speed.txt, ...");
  const auto file = [&](const char* name) { return (fs::path(dir) / name).string(); };
  const std::string parameters_path = file("parameters.txt");
  const std::map<std::string, double> p =
      fs::exists(parameters_path) ? ReadParameters(parameters_path) : std::map<std::string, double>{};
  const double to_deg = 180.0 / M_PI;
  const double dt = Setting(o.time_interval_s, p, "TimeInterval", parameters_path, "--time-interval-s", false);
  const double sigma_v = Setting(o.sigma_speed_mps, p, "sigv", parameters_path, "--sigma-speed-mps", true);
  const double sigma_w =
      Setting(o.sigma_turnrate_deg_s, p, "sigomega", parameters_path, "--sigma-turnrate-deg-s", true, to_deg) / to_deg;
  const double sigma_r = Setting(o.sigma_range_m, p, "sigr", parameters_path, "--sigma-range-m", false);
  const double sigma_b = Setting(o.sigma_bearing_deg, p, "sigtheta", parameters_path, "--sigma-bearing-deg", false, to_deg) / to_deg;

  const std::vector<double> speed = ReadSeries(file("store_speed.txt"));
  const std::vector<double> turnrate = ReadSeries(file("store_turnrate.txt"));
  if (speed.size() != turnrate.size())
    throw InputError(file("store_turnrate.txt"), 0,
                     std::to_string(turnrate.size()) + " turn rates for " + std::to_string(speed.size()) + " speeds",
                     "give one speed and one turn rate per step");
  // Bounds as every reader has them (core/limits.hpp): a finite 1e300 would overflow later.
  for (size_t k = 0; k < speed.size(); ++k)
    if (std::abs(speed[k] * dt) > limits::kMaxCoordinateM || std::abs(turnrate[k] * dt) > limits::kMaxAngleRad)
      throw InputError(file("store_speed.txt"), 0,
                       "step " + std::to_string(k + 1) + " moves farther than core/limits.hpp allows (speed " +
                           std::to_string(speed[k]) + ", turn rate " + std::to_string(turnrate[k]) + ")",
                       "check the speed and turn-rate files");
  LandmarkLog log;
  for (size_t k = 0; k < speed.size(); ++k) {
    const UnicycleStep step = IslsjfStep(speed[k], turnrate[k], dt, sigma_v, sigma_w);
    log.increments.push_back(step.increment);
    log.increment_covariances.push_back(step.covariance);
  }
  const int last_pose = static_cast<int>(speed.size());

  const std::string sensor_path = file("sensor_data.txt");
  double range_max = 0.0, widest_bearing = 0.0;
  std::set<int> beacons;
  for (const NumberRow& row : ParseNumberRows(ReadMaybeCompressedFile(sensor_path), sensor_path, kFormat)) {
    const std::vector<double>& v = row.values;
    const auto fail = [&](const std::string& problem) { throw InputError(sensor_path, row.line, problem, kFormat); };
    if (v.size() < 4) fail("expected `step id range bearing ...`, found " + std::to_string(v.size()) + " fields");
    if (v[0] != std::floor(v[0]) || v[0] < 1 || v[0] > last_pose + 1)
      fail("step " + std::to_string(v[0]) + " is not a whole number in 1 .. " + std::to_string(last_pose + 1));
    if (v[1] != std::floor(v[1]) || v[1] < 0 || v[1] > 1e9) fail("the beacon id must be a non-negative whole number");
    if (!(v[2] > 0) || v[2] > limits::kMaxCoordinateM)
      fail("range " + std::to_string(v[2]) + " m is not in (0, " + std::to_string(limits::kMaxCoordinateM) + "]");
    if (std::abs(v[3]) > limits::kMaxAngleRad) fail("bearing " + std::to_string(v[3]) + " rad is out of range");
    const double r = v[2], b = v[3];
    Eigen::Matrix2d J;  // d(x, y)/d(r, b) of the point (r cos b, r sin b)
    J << std::cos(b), -r * std::sin(b), std::sin(b), r * std::cos(b);
    log.sightings.push_back({static_cast<int>(v[0]) - 1, static_cast<int>(v[1]), Eigen::Vector2d(r * std::cos(b), r * std::sin(b)),
                             J * Eigen::Vector2d(sigma_r * sigma_r, sigma_b * sigma_b).asDiagonal() * J.transpose()});
    range_max = std::max(range_max, r);
    widest_bearing = std::max(widest_bearing, std::abs(std::remainder(b, 2 * M_PI)));
    beacons.insert(static_cast<int>(v[1]));
  }
  if (log.sightings.empty()) throw InputError(sensor_path, 0, "no observation", "give the run's sensor_data.txt");

  if (const std::string path = file("store_robotTrue.txt"); fs::exists(path)) {
    for (const NumberRow& row : ParseNumberRows(ReadMaybeCompressedFile(path), path, kFormat)) {
      if (row.values.size() != 3) throw InputError(path, row.line, "expected `x y phi`", kFormat);
      if (std::abs(row.values[0]) > limits::kMaxCoordinateM || std::abs(row.values[1]) > limits::kMaxCoordinateM ||
          std::abs(row.values[2]) > limits::kMaxAngleRad)
        throw InputError(path, row.line, "a pose beyond core/limits.hpp's bounds", kFormat);
      log.true_poses.emplace_back(row.values[0], row.values[1], row.values[2]);
    }
  }
  if (const std::string path = file("store_beaconsTrue.txt"); fs::exists(path)) {
    for (const NumberRow& row : ParseNumberRows(ReadMaybeCompressedFile(path), path, kFormat)) {
      const std::vector<double>& v = row.values;
      if (v.size() != 3 || v[0] != std::floor(v[0]) || v[0] < 0 || v[0] > 1e9)
        throw InputError(path, row.line, "expected `id x y` with a whole id >= 0", kFormat);
      if (std::abs(v[1]) > limits::kMaxCoordinateM || std::abs(v[2]) > limits::kMaxCoordinateM)
        throw InputError(path, row.line, "a beacon beyond core/limits.hpp's bounds", kFormat);
      log.true_landmarks[static_cast<int>(v[0])] = Eigen::Vector2d(v[1], v[2]);
    }
  }

  LandmarkLogOptions options;
  options.pose_period_s = dt;
  options.fov_deg = o.fov_deg ? *o.fov_deg : std::min(360.0, 2.0 * widest_bearing * to_deg);
  options.range_max_m = o.range_max_m ? *o.range_max_m : range_max;
  options.odometry_alpha = o.odometry_alpha;
  options.description = "the 2D-I-SLSJF simulation";
  fs::path name(dir);
  if (!name.has_filename()) name = name.parent_path();  // "sim_535/" names the run "sim_535"
  Stream s = AssembleLandmarkLog(log, name.string(), options);
  if (report)
    *report = {last_pose, static_cast<int>(log.sightings.size()), static_cast<int>(beacons.size()), dt,
               *options.range_max_m, options.fov_deg, !log.true_poses.empty()};
  return s;
}

}  // namespace slambox
