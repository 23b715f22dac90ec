// `slambox export STREAM --format jsonl|csv -o OUT`: a stream (or a scenario, simulated)
// as text for offline tools, in the event schema of the exec protocol
// (docs/exec_protocol.md). jsonl: the header line, one line per event, the finish line.
// csv: one row per event, the same keys as columns; arrays are space-separated.
// rawlog: an MRPT rawlog (slam/mrpt/mrpt_rawlog.hpp, through the MRPT plugin) for MRPT's tools.
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/rawlog_format.hpp"
#include "app/run.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/exec_protocol.hpp"

namespace slambox {

namespace {

enum class ExportFormat { kJsonl, kCsv, kRawlog };

struct ExportRequest {
  std::string input;
  std::uint64_t seed = 0;
  bool seed_given = false;
  std::vector<std::string> sets;
  ExportFormat format = ExportFormat::kJsonl;
  RawlogLayout rawlog_layout = RawlogLayout::kObservations;
  std::string output;
};

constexpr const char* kCsvColumns =
    "type,t_s,dx_m,dy_m,dtheta_rad,yaw_rate_rps,angle_min_rad,angle_increment_rad,range_min_m,range_max_m,"
    "ranges_m,valid,range_m,bearing_rad,id\n";

template <class T, class F>
void AppendList(const std::vector<T>& values, std::string& out, F&& append) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) out += ' ';
    append(values[i]);
  }
}

void AppendCsvRow(const SensorEvent& event, std::string& out) {
  const auto num = [&](double v) { AppendShortestNumber(v, out); };
  std::visit(
      [&](const auto& e) {
        using E = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<E, OdometryEvent>) {
          out += "odometry,", num(e.t_s), out += ',', num(e.delta.x), out += ',', num(e.delta.y), out += ',';
          num(e.delta.theta), out += ",,,,,,,,,,";
        } else if constexpr (std::is_same_v<E, LaserScanEvent>) {
          out += "scan,", num(e.t_s), out += ",,,,,", num(e.angle_min_rad), out += ',', num(e.angle_increment_rad);
          out += ',', num(e.range_min_m), out += ',', num(e.range_max_m), out += ',';
          AppendList(e.ranges_m, out, num);
          out += ',';
          AppendList(e.valid, out, [&](std::uint8_t v) { out += v ? '1' : '0'; });
          out += ",,,";
        } else if constexpr (std::is_same_v<E, LandmarkEvent>) {
          out += "landmarks,", num(e.t_s), out += ",,,,,,,,,,,";
          AppendList(e.observations, out, [&](const LandmarkObservation& o) { num(o.range_m); });
          out += ',';
          AppendList(e.observations, out, [&](const LandmarkObservation& o) { num(o.bearing_rad); });
          out += ',';
          AppendList(e.observations, out, [&](const LandmarkObservation& o) { out += std::to_string(o.id); });
        } else {
          out += "gyro,", num(e.t_s), out += ",,,,", num(e.yaw_rate_rps), out += ",,,,,,,,,";
        }
        out += '\n';
      },
      event);
}

void Export(const ExportRequest& r) {
  const Stream stream = LoadOrSimulate(r.input, r.seed, r.seed_given, SplitOverrides(r.sets).scenario);
  if (r.format == ExportFormat::kRawlog) {
    RawlogFormat().write(stream, r.output, r.rawlog_layout);
    std::cerr << "exported " << stream.events.size() << " events -> " << r.output << " (MRPT rawlog)\n";
    return;
  }
  std::string out;
  if (r.format == ExportFormat::kJsonl) {
    out = ExecHeaderLine(stream.header, "", nullptr, /*with_world=*/true) + "\n";
    for (const SensorEvent& e : stream.events) AppendEventLine(e, out);
    out += kFinishLine;
  } else {
    out = kCsvColumns;
    for (const SensorEvent& e : stream.events) AppendCsvRow(e, out);
  }
  WriteFileAtomic(r.output, out);
  std::cerr << "exported " << stream.events.size() << " events -> " << r.output << "\n";
}

}  // namespace

void AddExportCommand(CLI::App& app) {
  auto request = std::make_shared<ExportRequest>();
  auto* cmd = app.add_subcommand("export", "write a stream's events as JSON Lines, CSV (docs/exec_protocol.md) or an MRPT rawlog");
  cmd->add_option("input", request->input, "stream file, built-in scenario name or scenario YAML file")->required();
  cmd->add_option("--format", request->format,
                  "jsonl (header, events, finish), csv (one row per event) or rawlog (MRPT, for RawLogViewer / icp-slam)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, ExportFormat>{
          {"jsonl", ExportFormat::kJsonl}, {"csv", ExportFormat::kCsv}, {"rawlog", ExportFormat::kRawlog}}))
      ->default_str("jsonl");
  cmd->add_option("--rawlog-layout", request->rawlog_layout,
                  "rawlog only: observations (a flat list: RawLogViewer, icp-slam) or frames (action + sensory "
                  "frame pairs: MRPT's kf-slam and rbpf-slam apps)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, RawlogLayout>{
          {"observations", RawlogLayout::kObservations}, {"frames", RawlogLayout::kFrames}}))
      ->default_str("observations");
  cmd->add_option("--seed", request->seed, "simulation seed (scenarios only)")
      ->each([request](const std::string&) { request->seed_given = true; });
  cmd->add_option("--set", request->sets, "override a scenario key (scenarios only)");
  cmd->add_option("-o,--output", request->output, "file to write")->required();
  cmd->callback([request] { Export(*request); });
}

}  // namespace slambox
