// `slambox convert carmen LOG -o STREAM` (and `victoria-park`, `islsjf-sim`, `rawlog`, `graph`): a real log
// into a stream file, which `slambox run` replays like a simulated one (without ground truth,
// so pose metrics are null, unless a graph's --groundtruth gives it). CARMEN logs and MRPT
// rawlogs become streams the same way (datasets/laser_log.hpp); rawlogs are read by the MRPT
// plugin (app/rawlog_format.hpp). Victoria Park and pose-landmark graphs share
// datasets/landmark_log.hpp; a graph's chain is taken apart in app/graph_log.hpp.
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/commands.hpp"
#include "app/graph_log.hpp"
#include "app/rawlog_format.hpp"
#include "core/error.hpp"
#include "core/stream_io.hpp"
#include "datasets/carmen_log.hpp"
#include "datasets/islsjf_simulation.hpp"
#include "datasets/laser_log.hpp"
#include "datasets/landmark_log.hpp"
#include "datasets/victoria_park.hpp"

namespace slambox {

namespace {

struct ConvertRequest {
  std::string input, output;
  CarmenImportOptions carmen;
  LaserLogOptions rawlog;
  VictoriaParkImportOptions victoria;
  IslsjfSimulationOptions islsjf;
  GraphLogOptions graph_read;
  LandmarkLogOptions graph{.pose_period_s = 1.0, .fov_deg = 360.0};
  std::vector<double> alpha;
};

std::array<double, 4> Alpha(const std::vector<double>& given, std::array<double, 4> fallback) {
  if (given.empty()) return fallback;
  if (given.size() != 4)
    throw InputError("--odometry-alpha", 0, "expected 4 values", "write e.g. --odometry-alpha 0.05,0.005,0.05,0.005");
  for (const double a : given)
    if (!(a >= 0 && std::isfinite(a)))
      throw InputError("--odometry-alpha", 0, "value " + std::to_string(a) + " is not a finite number >= 0",
                       "write e.g. --odometry-alpha 0.05,0.005,0.05,0.005");
  return {given[0], given[1], given[2], given[3]};
}

void ConvertVictoriaPark(const ConvertRequest& r) {
  VictoriaParkImportOptions o = r.victoria;
  if (!r.alpha.empty()) o.odometry_alpha = Alpha(r.alpha, {});
  const Stream s = ReadVictoriaPark(r.input, o);
  WriteStream(s, r.output);
  long poses = 0, observations = 0;
  for (const SensorEvent& e : s.events) {
    poses += std::holds_alternative<OdometryEvent>(e);
    if (const auto* l = std::get_if<LandmarkEvent>(&e)) observations += static_cast<long>(l->observations.size());
  }
  const LandmarkSensorConfig& lm = *s.header.sensors.landmarks;
  std::ostringstream line;
  line.setf(std::ios::fixed);
  line.precision(3);
  line << "converted " << r.input << ": " << poses << " odometry steps, " << observations
       << " observations (known ids; median sigma_range " << lm.sigma_range_m << " m, sigma_bearing "
       << lm.sigma_bearing_deg << " deg, range max " << lm.range_max_m << " m"
       << (lm.detection_prob_known ? "" : ", detection probability not in the file") << "; odometry alpha";
  line.precision(6);
  for (double a : s.header.sensors.odometry->alpha) line << " " << a;
  line << (r.alpha.empty() ? " fitted to the file's covariances" : "") << ") -> " << r.output;
  std::cerr << line.str() << "\n";
}

void ConvertIslsjfSimulation(const ConvertRequest& r) {
  IslsjfSimulationOptions o = r.islsjf;
  if (!r.alpha.empty()) o.odometry_alpha = Alpha(r.alpha, {});
  IslsjfSimulationReport report;
  const Stream s = ReadIslsjfSimulation(r.input, o, &report);
  WriteStream(s, r.output);
  const LandmarkSensorConfig& lm = *s.header.sensors.landmarks;
  std::ostringstream line;
  line << "converted " << r.input << ": " << report.steps << " steps of " << report.time_interval_s << " s, "
       << report.observations << " observations of " << report.beacons_seen << " beacons (known ids; sigma_range "
       << lm.sigma_range_m << " m, sigma_bearing " << lm.sigma_bearing_deg << " deg, range max " << report.range_max_m
       << " m, fov " << report.fov_deg << " deg; odometry alpha";
  for (double a : s.header.sensors.odometry->alpha) line << " " << a;
  line << (r.alpha.empty() ? " fitted to the motion noise" : "") << ")"
       << (report.ground_truth ? ", with ground truth" : ", no ground truth") << " -> " << r.output;
  std::cerr << line.str() << "\n";
}

// One line for the user: what the laser log became.
void ReportLaserLog(const ConvertRequest& r, const Stream& s) {
  long odometry = 0, scans = 0, landmarks = 0;
  double path_m = 0.0;
  for (const SensorEvent& e : s.events) {
    if (const auto* odo = std::get_if<OdometryEvent>(&e)) ++odometry, path_m += odo->delta.translation().norm();
    scans += std::holds_alternative<LaserScanEvent>(e);
    landmarks += std::holds_alternative<LandmarkEvent>(e);
  }
  std::ostringstream line;
  line.setf(std::ios::fixed);
  line.precision(1);
  line << "converted " << r.input << ": " << s.header.duration_s << " s, " << path_m << " m by odometry, " << odometry
       << " odometry, " << scans << " scans";
  if (s.header.sensors.lidar)
    line << " (" << s.header.sensors.lidar->beams << " beams over " << s.header.sensors.lidar->fov_deg
         << " deg, range max " << s.header.sensors.lidar->range_max_m << " m)";
  if (landmarks) line << ", " << landmarks << " landmark messages";
  line << " -> " << r.output;
  std::cerr << line.str() << "\n";
}

void ConvertCarmen(const ConvertRequest& r) {
  CarmenImportOptions o = r.carmen;
  o.odometry_alpha = Alpha(r.alpha, o.odometry_alpha);
  CarmenImportReport report;
  const Stream s = ReadCarmenLog(r.input, o, &report);
  WriteStream(s, r.output);
  if (report.out_of_order_dropped > 0)
    std::cerr << "dropped " << report.out_of_order_dropped << " messages stamped before the log's clock (--out-of-order drop)\n";
  ReportLaserLog(r, s);
}

// A pose-landmark graph whose poses form one odometry chain (app/graph_log.hpp).
void ConvertGraph(const ConvertRequest& r) {
  const GraphLog g = ReadGraphLog(r.input, r.graph_read);
  const GraphLogReport& report = g.report;
  LandmarkLogOptions options = r.graph;
  if (!r.alpha.empty()) options.odometry_alpha = Alpha(r.alpha, {});
  options.description = report.isam_noise
                            ? std::string("the ") + NameOf(IsamNoiseNames(), *report.isam_noise) + "-noise graph"
                            : std::string("the g2o graph");
  const Stream s = AssembleLandmarkLog(g.log, r.input, options);
  WriteStream(s, r.output);
  const LandmarkSensorConfig& lm = *s.header.sensors.landmarks;
  std::ostringstream line;
  line << "converted " << r.input << ": " << report.odometry_steps << " odometry steps";
  if (report.reversed_steps > 0) line << " (" << report.reversed_steps << " stated backwards, inverted)";
  line << ", " << report.sightings << " landmark sightings of " << report.landmarks
       << " landmarks (known ids; median sigma_range " << lm.sigma_range_m << " m, sigma_bearing " << lm.sigma_bearing_deg
       << " deg)";
  if (report.isam_noise) line << ", noise read as " << NameOf(IsamNoiseNames(), *report.isam_noise);
  if (report.off_chain_edges > 0) line << ", " << report.off_chain_edges << " pose edges off the odometry chain left out";
  line << (g.log.true_poses.empty() ? ", no ground truth" : ", with ground truth") << " -> " << r.output;
  std::cerr << line.str() << "\n";
}

void ConvertRawlog(const ConvertRequest& r) {
  LaserLogOptions o = r.rawlog;
  o.odometry_alpha = Alpha(r.alpha, o.odometry_alpha);
  const Stream s = AssembleLaserLog(RawlogFormat().read(r.input), r.input, o);
  WriteStream(s, r.output);
  ReportLaserLog(r, s);
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
  carmen
      ->add_option("--out-of-order", r->carmen.out_of_order,
                   "a message stamped over 5 s before the log's clock so far: error (default) or drop it")
      ->transform(EnumTransformer(CarmenOutOfOrderNames()))
      ->default_str("error");
  carmen->callback([r] { ConvertCarmen(*r); });
  CLI::App* rawlog = cmd->add_subcommand(
      "rawlog", "MRPT rawlog (.rawlog, either layout): 2D laser scans, odometry, range-bearing landmarks (MRPT plugin)");
  rawlog->add_option("rawlog", r->input, "MRPT rawlog file")->required();
  rawlog->add_option("-o,--output", r->output, "stream file to write")->required();
  rawlog->add_option("--range-max-m", r->rawlog.range_max_m, "returns at or beyond are misses (default: the scans' maxRange)");
  rawlog->add_option("--sigma-range-m", r->rawlog.sigma_range_m, "range noise written into the stream header (default 0.01)");
  rawlog->add_option("--odometry-alpha", r->alpha, "odometry noise a1,a2,a3,a4 (Thrun's model; default 0.05,0.005,0.05,0.005)")
      ->delimiter(',');
  rawlog->callback([r] { ConvertRawlog(*r); });
  CLI::App* graph = cmd->add_subcommand(
      "graph", "pose-landmark graph (iSAM / GTSAM LANDMARK, g2o EDGE_SE2_XY) whose poses form one odometry chain");
  graph->add_option("graph", r->input, "graph file (slambox optimize reads the same formats)")->required();
  graph->add_option("-o,--output", r->output, "stream file to write")->required();
  graph->add_option("--groundtruth", r->graph_read.groundtruth,
                    "true poses ('id x y theta') and/or landmarks ('id x y'), or g2o/TORO vertex lines; may be given twice")
      ->check(CLI::ExistingFile);
  graph->add_option("--pose-period-s", r->graph.pose_period_s, "time between poses; graphs have none (default 1)");
  graph->add_option("--fov-deg", r->graph.fov_deg, "the detector's field of view, header only (default 360)");
  graph
      ->add_option("--noise", r->graph_read.noise,
                   "ODOMETRY / LANDMARK values, as `slambox optimize --noise`: sqrt-information (iSAM), covariance "
                   "(GTSAM), or auto: decided from the file")
      ->transform(EnumTransformer(IsamNoiseNames()))
      ->default_str("auto");
  graph->add_option("--odometry-alpha", r->alpha, "odometry noise a1,a2,a3,a4 (default: fitted to the edges' covariances)")
      ->delimiter(',');
  graph->callback([r] { ConvertGraph(*r); });
  CLI::App* vp = cmd->add_subcommand("victoria-park", "Victoria Park, preprocessed (VicPark_clean_data.txt): odometry + tree observations, known ids");
  vp->add_option("data", r->input, "VicPark_clean_data.txt (optionally .gz/.bz2)")->required();
  vp->add_option("-o,--output", r->output, "stream file to write")->required();
  vp->add_option("--pose-period-s", r->victoria.pose_period_s, "time between poses; the file has none (default 0.2)");
  vp->add_option("--odometry-alpha", r->alpha,
                 "odometry noise a1,a2,a3,a4 (Thrun's model; default: fitted to the file's odometry covariances)")
      ->delimiter(',');
  vp->callback([r] { ConvertVictoriaPark(*r); });
  CLI::App* sim = cmd->add_subcommand(
      "islsjf-sim", "a simulated range-bearing run of the 2D-I-SLSJF release (folder: sensor_data.txt, store_speed.txt, "
                    "store_turnrate.txt, parameters.txt; store_robotTrue.txt, store_beaconsTrue.txt as ground truth)");
  sim->add_option("folder", r->input, "the run's folder, e.g. landmark/sim_535")->required();
  sim->add_option("-o,--output", r->output, "stream file to write")->required();
  sim->add_option("--time-interval-s", r->islsjf.time_interval_s, "time between steps (default: parameters.txt TimeInterval)");
  sim->add_option("--sigma-speed-mps", r->islsjf.sigma_speed_mps, "speed noise, a standard deviation (default: sigv)");
  sim->add_option("--sigma-turnrate-deg-s", r->islsjf.sigma_turnrate_deg_s, "turn-rate noise (default: sigomega)");
  sim->add_option("--sigma-range-m", r->islsjf.sigma_range_m, "range noise (default: sigr)");
  sim->add_option("--sigma-bearing-deg", r->islsjf.sigma_bearing_deg, "bearing noise (default: sigtheta)");
  sim->add_option("--range-max-m", r->islsjf.range_max_m, "the detector's range (default: the farthest observation)");
  sim->add_option("--fov-deg", r->islsjf.fov_deg, "field of view (default: twice the widest bearing observed)");
  sim->add_option("--odometry-alpha", r->alpha, "odometry noise a1,a2,a3,a4 (default: fitted to the motion noise)")
      ->delimiter(',');
  sim->callback([r] { ConvertIslsjfSimulation(*r); });
}

}  // namespace slambox
