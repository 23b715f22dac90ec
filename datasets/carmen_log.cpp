#include "datasets/carmen_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "datasets/compressed_file.hpp"
#include "datasets/laser_log.hpp"

namespace slambox {

namespace {

constexpr double kDefaultRangeMaxM = 80.0;

struct OdometryPose {
  double ts = 0.0;  ///< the log's ipc timestamp [s]
  SE2 pose;         ///< robot in the odometry frame
  int order = 0;    ///< file order, to keep ties stable
};

struct Scan {
  double ts = 0.0;
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
  double range_max_m = 0.0;  ///< from ROBOTLASER1, else 0 (the default applies)
  std::vector<double> ranges_m;
  SE2 laser_pose, odometry_pose;
  int line = 0;
};

// Whitespace-separated tokens of one line, parsed on demand with the line number for errors.
class Tokens {
 public:
  Tokens(std::string_view line, const std::string& file, int line_number) : file_(file), line_(line_number) {
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      const size_t start = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i > start) tokens_.emplace_back(line.substr(start, i - start));
    }
  }
  size_t size() const { return tokens_.size(); }
  const std::string& word(size_t i) const { return tokens_[i]; }
  double Number(size_t i, const char* what) const {
    if (i >= tokens_.size()) Fail(std::string("the line ends before ") + what);
    char* end = nullptr;
    const double v = std::strtod(tokens_[i].c_str(), &end);
    if (end == tokens_[i].c_str() || *end != '\0' || !std::isfinite(v))
      Fail(std::string(what) + " is '" + tokens_[i] + "', not a finite number");
    return v;
  }
  int Count(size_t i, const char* what) const {
    const double v = Number(i, what);
    if (v < 0 || v != std::floor(v) || v > 100000) Fail(std::string(what) + " must be a whole count, got " + tokens_[i]);
    return static_cast<int>(v);
  }
  /// The ipc timestamp: third token from the end (ts host logger_ts).
  double Timestamp() const {
    if (tokens_.size() < 4) Fail("the line ends before its timestamp (ts host logger_ts)");
    const double ts = Number(tokens_.size() - 3, "the timestamp");
    if (std::abs(ts) > limits::kMaxTimestampS) Fail("the timestamp " + tokens_[tokens_.size() - 3] + " is out of range (|t| <= 1e10 s)");
    return ts;
  }
  [[noreturn]] void Fail(const std::string& problem) const {
    throw InputError(file_, line_, tokens_.empty() ? problem : tokens_[0] + ": " + problem,
                     "fix or delete this line (format in the log's header comments; datasets/carmen_log.hpp)");
  }

 private:
  std::vector<std::string> tokens_;
  const std::string& file_;
  int line_;
};

SE2 PoseAt(const Tokens& t, size_t i, const char* what) {
  const double x = t.Number(i, what), y = t.Number(i + 1, what), theta = t.Number(i + 2, what);
  // Bounded, so that increments between poses stay finite (core/limits.hpp).
  if (std::abs(x) > limits::kMaxCoordinateM || std::abs(y) > limits::kMaxCoordinateM ||
      std::abs(theta) > limits::kMaxAngleRad)
    t.Fail(std::string(what) + " (" + t.word(i) + ", " + t.word(i + 1) + ", " + t.word(i + 2) +
           ") is out of range (|x|, |y| <= 1e5 m, |theta| <= 1e4 rad)");
  return SE2(x, y, theta);
}

// n beams over the field of view: odd n puts the ends at +-fov/2, even n steps fov/n.
void FlaserGeometry(int n, double fov_rad, Scan& s) {
  s.angle_increment_rad = n > 1 ? (n % 2 == 1 ? fov_rad / (n - 1) : fov_rad / n) : 0.0;
  s.angle_min_rad = -0.5 * fov_rad;
}

struct ParsedLog {
  std::vector<OdometryPose> odometry;
  std::vector<Scan> scans;  ///< in file order
  std::map<std::string, double> params;
  int out_of_order_dropped = 0;
};

// The log's clock so far (the latest timestamp of a kept message), against which a message
// is out of order when it is earlier by more than kCarmenOutOfOrderToleranceS.
class LogClock {
 public:
  LogClock(const std::string& name, CarmenOutOfOrder policy) : name_(name), policy_(policy) {}
  /// True: keep the message. False: drop it (kDrop). Throws for kError.
  bool Keep(double ts, int line, const std::string& kind, int& dropped) {
    if (line_ > 0 && ts < latest_ - kCarmenOutOfOrderToleranceS) {
      if (policy_ == CarmenOutOfOrder::kDrop) return ++dropped, false;
      char problem[256];
      std::snprintf(problem, sizeof problem, "%s: timestamp %.6f is %.3f s before line %d's %.6f: the log's clock goes backwards",
                    kind.c_str(), ts, latest_ - ts, line_, latest_);
      throw InputError(name_, line, problem,
                       "convert with --out-of-order drop to skip such messages (a log written by a SLAM tool stamps the "
                       "corrected poses it writes after each scan 0), or fix the log's timestamps");
    }
    if (line_ == 0 || ts > latest_) latest_ = ts, line_ = line;
    return true;
  }

 private:
  const std::string& name_;
  CarmenOutOfOrder policy_;
  double latest_ = 0.0;
  int line_ = 0;  ///< the line of latest_ (0: no message yet)
};

// Scans must be ordered by their own clock: a log whose timestamps repeat for most
// consecutive scans (written with too few digits) cannot be ordered against its odometry.
void RequireScanClock(const ParsedLog& log, const std::string& name) {
  int equal = 0, first = 0;
  double first_ts = 0.0;
  for (size_t i = 1; i < log.scans.size(); ++i)
    if (log.scans[i].ts == log.scans[i - 1].ts && equal++ == 0) first = log.scans[i].line, first_ts = log.scans[i].ts;
  const int pairs = static_cast<int>(log.scans.size()) - 1;
  if (pairs >= 2 && 2 * equal > pairs) {
    char problem[256];
    std::snprintf(problem, sizeof problem,
                  "%d of %d consecutive scans share their timestamp (here %.6f): the log's clock is too coarse to order "
                  "scans and odometry",
                  equal, pairs, first_ts);
    throw InputError(name, first, problem, "re-export the log with its timestamps at millisecond resolution");
  }
}

ParsedLog ParseLines(const std::string& text, const std::string& name, const CarmenImportOptions& o) {
  ParsedLog log;
  LogClock clock(name, o.out_of_order);
  int line_number = 0, order = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    ++line_number;
    limits::CheckLineLength(name, line_number, line.size());
    if (line.empty() || line[0] == '#') continue;
    const Tokens t(line, name, line_number);
    if (t.size() == 0) continue;
    const std::string& kind = t.word(0);
    if (kind == "ODOM") {
      if (t.size() < 10) t.Fail("expected x y theta tv rv accel ts host logger_ts");
      const double ts = t.Timestamp();
      const SE2 pose = PoseAt(t, 1, "the odometry pose");
      if (clock.Keep(ts, line_number, kind, log.out_of_order_dropped)) log.odometry.push_back({ts, pose, order++});
    } else if (kind == "FLASER") {
      const int n = t.Count(1, "the number of readings");
      if (t.size() != static_cast<size_t>(n) + 11)
        t.Fail("expected " + std::to_string(n) + " readings, 6 pose values and ts host logger_ts (" +
               std::to_string(n + 11) + " fields), found " + std::to_string(t.size()));
      Scan s;
      s.ts = t.Timestamp();
      s.line = line_number;
      FlaserGeometry(n, o.fov_deg * M_PI / 180.0, s);
      for (int i = 0; i < n; ++i) s.ranges_m.push_back(t.Number(2 + i, "a range reading"));
      s.laser_pose = PoseAt(t, 2 + n, "the laser pose");
      s.odometry_pose = PoseAt(t, 5 + n, "the odometry pose");
      if (!clock.Keep(s.ts, line_number, kind, log.out_of_order_dropped)) continue;
      log.odometry.push_back({s.ts, s.odometry_pose, order++});
      log.scans.push_back(std::move(s));
    } else if (kind == "ROBOTLASER1") {
      const int n = t.Count(8, "the number of readings");
      const int m = t.Count(9 + n, "the number of remissions");
      if (t.size() != static_cast<size_t>(n + m) + 24)
        t.Fail("expected " + std::to_string(n + m + 24) + " fields for " + std::to_string(n) + " readings and " +
               std::to_string(m) + " remissions, found " + std::to_string(t.size()));
      Scan s;
      s.ts = t.Timestamp();
      s.line = line_number;
      s.angle_min_rad = t.Number(2, "start_angle");
      s.angle_increment_rad = t.Number(4, "the angular resolution");
      // Bounded, so that the header's field of view (n x resolution) stays finite (found by fuzz_carmen).
      if (std::abs(s.angle_min_rad) > limits::kMaxAngleRad || std::abs(s.angle_increment_rad) > limits::kMaxAngleRad)
        t.Fail("start_angle " + t.word(2) + " or angular resolution " + t.word(4) + " is out of range (|angle| <= 1e4 rad)");
      s.range_max_m = t.Number(5, "max_range");
      for (int i = 0; i < n; ++i) s.ranges_m.push_back(t.Number(9 + i, "a range reading"));
      s.laser_pose = PoseAt(t, 10 + n + m, "the laser pose");
      s.odometry_pose = PoseAt(t, 13 + n + m, "the robot pose");
      if (!clock.Keep(s.ts, line_number, kind, log.out_of_order_dropped)) continue;
      log.odometry.push_back({s.ts, s.odometry_pose, order++});
      log.scans.push_back(std::move(s));
    } else if (kind == "PARAM" && t.size() >= 3) {
      char* e = nullptr;
      const double v = std::strtod(t.word(2).c_str(), &e);
      if (e != t.word(2).c_str() && *e == '\0' && std::isfinite(v)) log.params[t.word(1)] = v;
    }
  }
  return log;
}

}  // namespace

const EnumNames<CarmenOutOfOrder>& CarmenOutOfOrderNames() {
  static const EnumNames<CarmenOutOfOrder> names = {{CarmenOutOfOrder::kError, "error"}, {CarmenOutOfOrder::kDrop, "drop"}};
  return names;
}

Stream ParseCarmenLog(const std::string& text, const std::string& name, const CarmenImportOptions& o,
                      CarmenImportReport* report) {
  if (!(o.dt_s > 0) || !(o.fov_deg > 0 && o.fov_deg <= 360) || o.range_max_m < 0 || !(o.range_min_m >= 0))
    throw InputError(name, 0, "invalid import options (dt_s > 0, 0 < fov_deg <= 360, range_max_m >= 0)",
                     "check the --fov-deg / --range-max-m values");
  ParsedLog log = ParseLines(text, name, o);
  if (log.scans.empty())
    throw InputError(name, 0, "no FLASER or ROBOTLASER1 message: nothing to convert",
                     "give a CARMEN laser log (.clf / .log, optionally .gz or .bz2)");
  RequireScanClock(log, name);
  if (report) report->out_of_order_dropped = log.out_of_order_dropped;

  LaserLog out;
  out.format = "CARMEN log";
  // The laser's mounting, from the first scan's (laser pose, odometry pose) pair.
  out.T_robot_laser = Between(log.scans.front().odometry_pose, log.scans.front().laser_pose);
  for (const OdometryPose& p : log.odometry) out.odometry.push_back({p.ts, p.pose});
  for (Scan& in : log.scans)
    out.scans.push_back({in.ts, in.angle_min_rad, in.angle_increment_rad, in.range_max_m, std::move(in.ranges_m), {}});
  const auto param = log.params.find("robot_front_laser_max");
  const LaserLogOptions options{.range_max_m = o.range_max_m, .range_min_m = o.range_min_m,
                                .sigma_range_m = o.sigma_range_m, .odometry_alpha = o.odometry_alpha, .dt_s = o.dt_s};
  return AssembleLaserLog(std::move(out), name, options, param == log.params.end() ? 0.0 : param->second);
}

Stream ReadCarmenLog(const std::string& path, const CarmenImportOptions& options, CarmenImportReport* report) {
  return ParseCarmenLog(ReadMaybeCompressedFile(path), path, options, report);
}

}  // namespace slambox
