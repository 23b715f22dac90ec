// `slambox convert carmen LOG -o STREAM`: a real log into a stream file, which `slambox
// run` replays like a simulated one (without ground truth, so pose metrics are null).
#include <iostream>
#include <memory>
#include <sstream>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "core/stream_io.hpp"
#include "datasets/carmen_log.hpp"

namespace slambox {

namespace {

struct ConvertRequest {
  std::string input, output;
  CarmenImportOptions carmen;
  std::vector<double> alpha;
};

void ConvertCarmen(const ConvertRequest& r) {
  CarmenImportOptions o = r.carmen;
  if (!r.alpha.empty()) {
    if (r.alpha.size() != 4)
      throw InputError("--odometry-alpha", 0, "expected 4 values", "write e.g. --odometry-alpha 0.05,0.005,0.05,0.005");
    for (size_t i = 0; i < 4; ++i) o.odometry_alpha[i] = r.alpha[i];
  }
  const Stream s = ReadCarmenLog(r.input, o);
  WriteStream(s, r.output);
  long odometry = 0, scans = 0;
  double path_m = 0.0;
  for (const SensorEvent& e : s.events) {
    if (const auto* odo = std::get_if<OdometryEvent>(&e)) ++odometry, path_m += odo->delta.translation().norm();
    scans += std::holds_alternative<LaserScanEvent>(e);
  }
  std::ostringstream line;
  line.setf(std::ios::fixed);
  line.precision(1);
  line << "converted " << r.input << ": " << s.header.duration_s << " s, " << path_m << " m by odometry, " << odometry
       << " odometry, " << scans << " scans (" << s.header.sensors.lidar->beams << " beams over "
       << s.header.sensors.lidar->fov_deg << " deg, range max " << s.header.sensors.lidar->range_max_m << " m) -> "
       << r.output;
  std::cerr << line.str() << "\n";
}

}  // namespace

void AddConvertCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("convert", "convert a real dataset into a stream file for `slambox run`");
  cmd->require_subcommand(1);
  auto r = std::make_shared<ConvertRequest>();
  CLI::App* carmen = cmd->add_subcommand("carmen", "CARMEN laser log (.clf/.log, .gz/.bz2): ODOM, FLASER, ROBOTLASER1");
  carmen->add_option("log", r->input, "CARMEN log file")->required();
  carmen->add_option("-o,--output", r->output, "stream file to write")->required();
  carmen->add_option("--fov-deg", r->carmen.fov_deg, "FLASER field of view, centred ahead (default 180)");
  carmen->add_option("--range-max-m", r->carmen.range_max_m,
                     "returns at or beyond are misses (default: the log's PARAM robot_front_laser_max, else 80)");
  carmen->add_option("--sigma-range-m", r->carmen.sigma_range_m, "range noise written into the stream header (default 0.01)");
  carmen->add_option("--odometry-alpha", r->alpha, "odometry noise a1,a2,a3,a4 (Thrun's model; default 0.05,0.005,0.05,0.005)")
      ->delimiter(',');
  carmen->callback([r] { ConvertCarmen(*r); });
}

}  // namespace slambox
