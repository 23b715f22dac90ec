#include "slam/mrpt/mrpt_graphslam.hpp"

// This file instantiates CLoopCloserERD, so it is compiled with -fno-tree-slp-vectorize
// (slam/mrpt/CMakeLists.txt): with GCC 12's SLP vectorizer, CLoopCloserERD's constructor
// stores two doubles at once with an aligned SSE store (movaps) to a member that is only
// 8-byte aligned, and the first `new CLoopCloserERD` ends the process with SIGSEGV (Debian's
// own `graphslam-engine` crashes the same way). See slam/mrpt/README.md.
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/graphs/CNetworkOfPoses.h>
#include <mrpt/opengl/CDisk.h>  // used by CLevMarqGSO_impl.h, which does not include it
#include <mrpt/graphslam/CGraphSlamEngine.h>
#include <mrpt/graphslam/ERD/CLoopCloserERD.h>
#include <mrpt/graphslam/GSO/CLevMarqGSO.h>
#include <mrpt/graphslam/NRD/CFixedIntervalsNRD.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>

#include "core/error.hpp"
#include "core/file_status.hpp"
#include "slam/mrpt/mrpt_convert.hpp"

#ifndef SLAMBOX_MRPT_GRAPHSLAM_INI
#error "SLAMBOX_MRPT_GRAPHSLAM_INI (the path of laser_odometry_LC.ini) is set by slam/mrpt/CMakeLists.txt"
#endif

namespace slambox {

namespace mb = mrpt_bridge;
namespace fs = std::filesystem;
using Graph = mrpt::graphs::CNetworkOfPoses2DInf;

namespace {

constexpr const char* kNrd = "NodeRegistrationDeciderParameters";
constexpr const char* kErd = "EdgeRegistrationDeciderParameters";
constexpr const char* kGso = "OptimizerParameters";
constexpr const char* kGeneral = "GeneralConfiguration";
constexpr const char* kIcp = "ICP";

/// One .ini key per parameter (both directions: reading the defaults, writing the engine's file).
template <class F>
void ForEachIniKey(MrptGraphSlamConfig& c, F&& f) {
  f(kNrd, "registration_max_distance", c.registration_max_distance_m);
  f(kNrd, "registration_max_angle", c.registration_max_angle_deg);
  f(kErd, "prev_nodes_for_ICP", c.icp_prev_nodes);
  f(kGeneral, "LC_min_nodeid_diff", c.lc_min_nodeid_diff);
  f(kErd, "LC_min_remote_nodes", c.lc_min_remote_nodes);
  f(kErd, "LC_eigenvalues_ratio_thresh", c.lc_eigenvalues_ratio_thresh);
  f(kErd, "partitionThreshold", c.partition_threshold);
  f(kGso, "optimization_distance", c.optimization_distance_m);
  f(kGso, "max_iterations", c.optimizer_max_iterations);
  f(kIcp, "maxIterations", c.icp_max_iterations);
  f(kIcp, "thresholdDist", c.icp_threshold_dist_m);
  f(kIcp, "thresholdAng_DEG", c.icp_threshold_ang_deg);
  f(kIcp, "ALFA", c.icp_alfa);
  f(kIcp, "smallestThresholdDist", c.icp_smallest_threshold_dist_m);
  f(kIcp, "corresponding_points_decimation", c.icp_points_decimation);
}

void RequireIni(const std::string& path) {
  if (!IsRegularFile(path))
    throw InputError(path, 0, "MRPT's graphslam-engine configuration laser_odometry_LC.ini not found",
                     "install Debian's mrpt-common (scripts/setup.sh) and rebuild slambox");
}

/// Points stdin and stdout at /dev/null while MRPT runs, and back after. The engine's
/// constructor calls mrpt::system::pause() (prints and waits for a key on stdin) when its
/// constraint class name is not in its list of tested ones, which in MRPT 2.5 is always
/// (the list has "CPosePDFGaussianInf", the class reports "mrpt::poses::CPosePDFGaussianInf");
/// its loggers and profiler also print to stdout.
class MuteStdio {
 public:
  MuteStdio() {
    std::cout.flush();
    std::fflush(stdout);
    saved_in_ = dup(STDIN_FILENO);
    saved_out_ = dup(STDOUT_FILENO);
    const int null = open("/dev/null", O_RDWR | O_CLOEXEC);
    if (null >= 0) {
      dup2(null, STDIN_FILENO);
      dup2(null, STDOUT_FILENO);
      close(null);
    }
  }
  ~MuteStdio() {
    std::cout.flush();
    std::fflush(stdout);
    if (saved_in_ >= 0) dup2(saved_in_, STDIN_FILENO), close(saved_in_);
    if (saved_out_ >= 0) dup2(saved_out_, STDOUT_FILENO), close(saved_out_);
  }
  MuteStdio(const MuteStdio&) = delete;
  MuteStdio& operator=(const MuteStdio&) = delete;

 private:
  int saved_in_ = -1, saved_out_ = -1;
};

std::string Text(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

}  // namespace

std::string MrptGraphSlamIniPath() { return SLAMBOX_MRPT_GRAPHSLAM_INI; }

MrptGraphSlamConfig ReadMrptGraphSlamIni(const std::string& path) {
  RequireIni(path);
  const mrpt::config::CConfigFile file(path);
  MrptGraphSlamConfig c;
  ForEachIniKey(c, [&](const char* section, const char* key, auto& field) {
    using T = std::decay_t<decltype(field)>;
    if constexpr (std::is_same_v<T, int>)
      field = file.read_int(section, key, field, false);
    else
      field = file.read_double(section, key, field, false);
  });
  // MRPT reads the ICP variant as an enum name (TConfigParameters: "icpClassic", ...).
  c.icp_levenberg_marquardt = file.read_string(kIcp, "ICP_algorithm", "icpClassic", false) == "icpLevenbergMarquardt";
  return c;
}

std::string WriteMrptGraphSlamIni(const std::string& path, const MrptGraphSlamConfig& config) {
  RequireIni(path);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  mrpt::config::CConfigFileMemory ini(text.str());
  MrptGraphSlamConfig c = config;
  ForEachIniKey(c, [&](const char* section, const char* key, auto& field) {
    ini.write(section, key, Text(static_cast<double>(field)));
  });
  ini.write(kIcp, "ICP_algorithm", std::string(c.icp_levenberg_marquardt ? "icpLevenbergMarquardt" : "icpClassic"));
  for (const char* section : {kGeneral, kNrd, kErd, kGso}) ini.write(section, "class_verbosity", std::string("3"));
  ini.write(kGso, "optimization_on_second_thread", std::string("false"));  // deterministic
  ini.write(kGeneral, "save_3DScene", std::string("false"));
  ini.write(kGeneral, "save_graph", std::string("false"));
  std::string out;
  ini.getContent(out);
  return out;
}

void BindParams(MrptGraphSlamConfig& c, ParamBinder& b) {
  b.Bind("registration_max_distance_m", c.registration_max_distance_m, "m", "CFixedIntervalsNRD: odometry distance between nodes", Above(0));
  b.Bind("registration_max_angle_deg", c.registration_max_angle_deg, "deg", "CFixedIntervalsNRD: odometry rotation between nodes", Above(0));
  b.Bind("icp_prev_nodes", c.icp_prev_nodes, "-", "CLoopCloserERD prev_nodes_for_ICP: ICP edges to this many previous nodes", AtLeast(0));
  b.Bind("lc_min_nodeid_diff", c.lc_min_nodeid_diff, "-", "LC_min_nodeid_diff: nodes apart for an edge to be a loop closure", AtLeast(1));
  b.Bind("lc_min_remote_nodes", c.lc_min_remote_nodes, "-", "CLoopCloserERD LC_min_remote_nodes: remote nodes a partition needs to be examined", AtLeast(1));
  b.Bind("lc_eigenvalues_ratio_thresh", c.lc_eigenvalues_ratio_thresh, "-", "CLoopCloserERD: consistency eigenvalue ratio to accept a set of loop closures", Above(0));
  b.Bind("partition_threshold", c.partition_threshold, "-", "map partitioning (CIncrementalMapPartitioner) partitionThreshold", Between(0, 1));
  b.Bind("optimization_distance_m", c.optimization_distance_m, "m", "CLevMarqGSO: optimize the nodes within this distance of the newest", Above(0));
  b.Bind("optimizer_max_iterations", c.optimizer_max_iterations, "-", "CLevMarqGSO max_iterations", AtLeast(1));
  b.Bind("icp_max_iterations", c.icp_max_iterations, "-", "CICP maxIterations", AtLeast(1));
  b.Bind("icp_threshold_dist_m", c.icp_threshold_dist_m, "m", "CICP thresholdDist: initial pairing distance", Above(0));
  b.Bind("icp_threshold_ang_deg", c.icp_threshold_ang_deg, "deg", "CICP thresholdAng: pairing distance per metre of range", AtLeast(0));
  b.Bind("icp_alfa", c.icp_alfa, "-", "CICP ALFA: threshold shrink factor at convergence", Between(0, 1));
  b.Bind("icp_smallest_threshold_dist_m", c.icp_smallest_threshold_dist_m, "m", "CICP smallestThresholdDist", Above(0));
  b.Bind("icp_points_decimation", c.icp_points_decimation, "-", "CICP corresponding_points_decimation", AtLeast(1));
  b.Bind("icp_levenberg_marquardt", c.icp_levenberg_marquardt, "-", "CICP ICP_algorithm: icpLevenbergMarquardt (true) or icpClassic (false)");
  b.Bind("occupied_below_free_prob", c.occupied_below_free_prob, "-", "grid cells with p(free) below this are map points", Between(0, 1));
}

struct MrptGraphSlam::State {
  // The engine keeps raw pointers to the deciders and the optimizer and never deletes
  // them: they are destroyed after it (~State).
  std::unique_ptr<mrpt::graphslam::deciders::CFixedIntervalsNRD<Graph>> node_registrar;
  std::unique_ptr<mrpt::graphslam::deciders::CLoopCloserERD<Graph>> edge_registrar;
  std::unique_ptr<mrpt::graphslam::optimizers::CLevMarqGSO<Graph>> optimizer;
  std::unique_ptr<mrpt::graphslam::CGraphSlamEngine<Graph>> engine;
  std::array<double, 4> alpha{};
  double sigma_range_m = 0.01;
  SE2 start;
  mb::OdometryAccumulator pending;  ///< odometry since the last scan
  SE2 odometry;                     ///< raw odometry composed since the start (start frame)
  std::map<mrpt::graphs::TNodeID, SE2> node_odometry;  ///< `odometry` at each node's scan
  struct ScanRecord {
    double t_s;
    SE2 odometry;
    mrpt::graphs::TNodeID node;  ///< the last node registered at or before the scan
  };
  std::vector<ScanRecord> scans;
  size_t rawlog_entry = 0;
  Estimate estimate;
  ~State() {
    const MuteStdio mute;  // each one's profiler (CTimeLogger) prints its table at destruction
    engine.reset();
    optimizer.reset();
    edge_registrar.reset();
    node_registrar.reset();
  }
};

MrptGraphSlam::MrptGraphSlam(const MrptGraphSlamConfig& config, std::string ini_path)
    : config_(config), ini_path_(std::move(ini_path)) {}
MrptGraphSlam::~MrptGraphSlam() = default;

void MrptGraphSlam::Start(const StreamHeader& header) {
  mb::SeedMrptRandom(header.seed);
  state_ = std::make_unique<State>();
  State& s = *state_;
  s.start = header.start_pose;
  s.alpha = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  if (header.sensors.lidar) s.sigma_range_m = header.sensors.lidar->sigma_range_m;
  // The engine reads its configuration from a file: the installed .ini with this module's values.
  const std::string text = WriteMrptGraphSlamIni(ini_path_, config_);
  std::string file = (fs::temp_directory_path() / "slambox-mrpt-graphslam-XXXXXX").string();
  const int fd = mkstemp(file.data());
  bool written = fd >= 0 && write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  if (fd >= 0) written = close(fd) == 0 && written;
  if (!written) {
    std::error_code ignored;
    if (fd >= 0) fs::remove(file, ignored);  // no partial file left behind
    throw InputError(file, 0, "cannot write the engine's configuration file", "check that the temporary folder is writable");
  }
  try {
    const MuteStdio mute;
    s.node_registrar = std::make_unique<mrpt::graphslam::deciders::CFixedIntervalsNRD<Graph>>();
    s.edge_registrar = std::make_unique<mrpt::graphslam::deciders::CLoopCloserERD<Graph>>();
    s.optimizer = std::make_unique<mrpt::graphslam::optimizers::CLevMarqGSO<Graph>>();
    s.engine = std::make_unique<mrpt::graphslam::CGraphSlamEngine<Graph>>(
        file, "", "", nullptr, s.node_registrar.get(), s.edge_registrar.get(), s.optimizer.get());
  } catch (...) {
    fs::remove(file);
    throw;
  }
  fs::remove(file);  // read in the constructor only
  s.node_odometry[0] = SE2();  // the root node is the start
}

void MrptGraphSlam::OnOdometry(const OdometryEvent& odometry) {
  state_->pending.Add(odometry, state_->alpha);
  state_->odometry = state_->odometry * odometry.delta;
}

void MrptGraphSlam::OnLaserScan(const LaserScanEvent& scan) {
  State& s = *state_;
  if (s.pending.empty) s.pending.t_s = scan.t_s;  // a zero motion: the engine needs an action
  auto actions = std::make_shared<mrpt::obs::CActionCollection>();
  actions->insert(mb::ToMrptAction(s.pending, mb::ActionNoiseFloor{}));
  s.pending.Reset();
  auto frame = std::make_shared<mrpt::obs::CSensoryFrame>();
  auto obs = std::make_shared<mrpt::obs::CObservation2DRangeScan>(mb::ToMrptScan(scan, s.sigma_range_m));
  obs->timestamp = mb::ToMrptTime(scan.t_s);
  frame->insert(obs);
  mrpt::obs::CObservation::Ptr no_observation;  // the action-observation format
  const size_t nodes_before = s.engine->getGraph().nodeCount();
  {
    const MuteStdio mute;
    s.engine->_execGraphSlamStep(actions, frame, no_observation, s.rawlog_entry);
  }
  ++s.rawlog_entry;
  const size_t nodes = s.engine->getGraph().nodeCount();
  if (nodes > nodes_before) s.node_odometry[static_cast<mrpt::graphs::TNodeID>(nodes - 1)] = s.odometry;
  s.scans.push_back({scan.t_s, s.odometry, s.node_odometry.rbegin()->first});
}

Estimate MrptGraphSlam::Finish() {
  State& s = *state_;
  const auto nodes = s.engine->getRobotEstimatedTrajectory();  // optimized, start frame
  const auto pose_of = [&](mrpt::graphs::TNodeID id) {
    const auto it = nodes.find(id);
    return it == nodes.end() ? SE2() : mb::FromMrpt(it->second);
  };
  const auto add = [&](double t_s, const SE2& pose_start) {
    const PoseEstimate pe{t_s, mb::ToWorld(s.start, pose_start), Eigen::Matrix3d::Zero(), false};
    if (!s.estimate.trajectory.empty() && s.estimate.trajectory.back().t_s == pe.t_s)
      s.estimate.trajectory.back() = pe;  // a scan at t = 0 is the start
    else
      s.estimate.trajectory.push_back(pe);
  };
  add(0.0, SE2());
  for (const State::ScanRecord& r : s.scans)
    add(r.t_s, pose_of(r.node) * Between(s.node_odometry.at(r.node), r.odometry));
  std::map<std::string, int> edges;
  s.edge_registrar->getEdgesStats(&edges);
  s.estimate.diagnostics["graph_nodes"].push_back({s.scans.empty() ? 0.0 : s.scans.back().t_s, static_cast<double>(nodes.size())});
  for (const auto& [type, count] : edges)
    s.estimate.diagnostics["edges_" + type].push_back({s.scans.empty() ? 0.0 : s.scans.back().t_s, static_cast<double>(count)});
  if (nodes.size() > 1) {
    auto grid = mrpt::maps::COccupancyGridMap2D::Create();
    {
      const MuteStdio mute;
      s.engine->getMap(grid);
    }
    for (unsigned iy = 0; iy < grid->getSizeY(); ++iy)
      for (unsigned ix = 0; ix < grid->getSizeX(); ++ix)
        if (grid->getCell(static_cast<int>(ix), static_cast<int>(iy)) < config_.occupied_below_free_prob)
          s.estimate.map_points.push_back(s.start * Eigen::Vector2d(grid->idx2x(ix), grid->idx2y(iy)));
  }
  return std::move(s.estimate);
}

ModuleInfo MrptGraphSlamModule() {
  const std::string name = "mrpt-graphslam";
  ModuleInfo info;
  info.name = name;
  info.description =
      "MRPT 2.5 CGraphSlamEngine (laser_odometry_LC.ini): ICP edges, loop closer, LM optimizer; slow, cost grows "
      "with the graph (slam/mrpt/README.md)";
  info.needs = {.odometry = true, .lidar = true};
  info.in_all = false;  // minutes to hours per stream (slam/mrpt/README.md): run only when named
  // Defaults: the installed .ini, read when listed or built (not at plugin load).
  info.params = [] {
    MrptGraphSlamConfig c = ReadMrptGraphSlamIni(MrptGraphSlamIniPath());
    ParamBinder b;
    BindParams(c, b);
    return b.List();
  };
  info.create = [name](const ParamOverrides& overrides) -> std::unique_ptr<SlamModule> {
    MrptGraphSlamConfig c = ReadMrptGraphSlamIni(MrptGraphSlamIniPath());
    ParamBinder b;
    BindParams(c, b);
    b.Apply(overrides, name);
    b.Validate(name);
    return std::make_unique<MrptGraphSlam>(c);
  };
  return info;
}

}  // namespace slambox
