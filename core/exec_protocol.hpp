#pragma once
// The `exec` protocol, version 1 (docs/exec_protocol.md): stream events as JSON Lines to a
// child process, and the child's answers (poses, landmarks, diagnostics, done) parsed with
// strict validation. Pure text in, text out: the process plumbing is app/child_process.
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/estimate.hpp"
#include "core/flat_json.hpp"
#include "core/stream.hpp"

namespace slambox {

inline constexpr int kExecProtocolVersion = 1;

/// The header line (no trailing newline). `params` is the module's parameter object; the
/// world is included only when `with_world` (modules that localize in a known map). An
/// empty `module` (stream export) leaves out "module" and "params".
std::string ExecHeaderLine(const StreamHeader& header, const std::string& module,
                           const nlohmann::json& params, bool with_world);
/// Appends the shortest round-trip text of `v`, always with a '.' or an exponent (so every
/// reader, Python's json included, reads a float); a non-finite value as null.
void AppendShortestNumber(double v, std::string& out);
/// Appends one event line (with '\n'); numbers are shortest round-trip.
void AppendEventLine(const SensorEvent& event, std::string& out);
inline constexpr std::string_view kFinishLine = "{\"type\":\"finish\"}\n";

/// A child's answer that breaks the protocol (status `failed`).
class ExecProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Accumulates the child's stdout lines into an Estimate.
class ExecAnswerParser {
 public:
  /// Parses stdout line number `line_number` (1-based, without '\n'). `latest_event_t_s`
  /// is the time of the last event sent so far (a pose may not be later). Throws
  /// ExecProtocolError, or ModuleDiverged (core/error.hpp) for a
  /// non-finite pose or landmark, naming the line.
  void ParseLine(std::string_view line, long line_number, double latest_event_t_s);
  bool done() const { return done_; }
  Estimate TakeEstimate() { return std::move(estimate_); }

 private:
  Estimate estimate_;
  std::vector<int> landmark_ids_;  ///< sorted, to reject duplicates
  FlatObject object_;              ///< reused between lines (no allocation per line)
  bool done_ = false;
};

}  // namespace slambox
