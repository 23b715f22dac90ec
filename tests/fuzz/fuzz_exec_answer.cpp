// The `exec` protocol's answer reader (core/exec_protocol): a child's stdout, line by line.
// Contract: each line is accepted or refused with ExecProtocolError (status `failed`) or
// ModuleDiverged (non-finite numbers, status `diverged`) — never another exception — and
// the accepted estimate is finite with strictly increasing pose times no later than the
// latest event, and unique landmark ids.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "core/exec_protocol.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {
constexpr double kLatestEventTime_s = 100.0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slambox;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  ExecAnswerParser parser;
  long line_number = 0;
  std::size_t begin = 0;
  try {
    while (begin <= text.size()) {
      std::size_t end = text.find('\n', begin);
      if (end == std::string_view::npos) end = text.size();
      parser.ParseLine(text.substr(begin, end - begin), ++line_number, kLatestEventTime_s);
      begin = end + 1;
    }
  } catch (const ExecProtocolError&) {
  } catch (const ModuleDiverged&) {
  }
  const Estimate estimate = parser.TakeEstimate();
  for (std::size_t i = 0; i < estimate.trajectory.size(); ++i) {
    const auto& p = estimate.trajectory[i];
    if (!std::isfinite(p.t_s) || !std::isfinite(p.pose.x) || !std::isfinite(p.pose.y) || !std::isfinite(p.pose.theta))
      fuzz::Finding("non-finite pose accepted");
    if (p.has_covariance && !p.covariance.allFinite()) fuzz::Finding("non-finite pose covariance accepted");
    if (p.t_s > kLatestEventTime_s) fuzz::Finding("pose later than the latest event accepted");
    if (i > 0 && !(p.t_s > estimate.trajectory[i - 1].t_s)) fuzz::Finding("pose times not strictly increasing");
  }
  for (std::size_t i = 0; i < estimate.landmarks.size(); ++i) {
    const auto& l = estimate.landmarks[i];
    if (!l.position.allFinite() || (l.has_covariance && !l.covariance.allFinite()))
      fuzz::Finding("non-finite landmark accepted");
    for (std::size_t j = 0; j < i; ++j)
      if (estimate.landmarks[i].id == estimate.landmarks[j].id) fuzz::Finding("duplicate landmark id accepted");
  }
  return 0;
}
