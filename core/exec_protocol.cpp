#include "core/exec_protocol.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>

#include "core/error.hpp"
#include "core/json_io.hpp"

namespace slambox {

using nlohmann::json;

std::string ExecHeaderLine(const StreamHeader& header, const std::string& module, const json& params,
                           bool with_world) {
  json j = {{"protocol", "slambox-exec"},
            {"version", kExecProtocolVersion},
            {"module", module},
            {"params", params.is_null() ? json::object() : params},
            {"scenario", header.scenario_name},
            {"seed", header.seed},
            {"dt_s", header.dt_s},
            {"duration_s", header.duration_s},
            {"start_pose", ToJson(header.start_pose)},
            {"sensors", ToJson(header.sensors)}};
  if (with_world) j["world"] = ToJson(header.world);
  if (module.empty()) j.erase("module"), j.erase("params");
  return "{\"type\":\"header\"," + j.dump().substr(1);  // "type" first, as in every line
}

namespace {

}  // namespace

void AppendShortestNumber(double v, std::string& out) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  const std::string_view s(buf, static_cast<std::size_t>(r.ptr - buf));
  out += s;
  if (s.find_first_of(".e") == std::string_view::npos) out += ".0";
}

namespace {

void AppendInt(long v, std::string& out) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void Key(std::string_view key, std::string& out) {
  out += ",\"";
  out += key;
  out += "\":";
}

}  // namespace

void AppendEventLine(const SensorEvent& event, std::string& out) {
  std::visit(
      [&](const auto& e) {
        using E = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<E, OdometryEvent>) {
          out += "{\"type\":\"odometry\"";
          Key("t_s", out), AppendShortestNumber(e.t_s, out);
          Key("dx_m", out), AppendShortestNumber(e.delta.x, out);
          Key("dy_m", out), AppendShortestNumber(e.delta.y, out);
          Key("dtheta_rad", out), AppendShortestNumber(e.delta.theta, out);
        } else if constexpr (std::is_same_v<E, LaserScanEvent>) {
          out += "{\"type\":\"scan\"";
          Key("t_s", out), AppendShortestNumber(e.t_s, out);
          Key("angle_min_rad", out), AppendShortestNumber(e.angle_min_rad, out);
          Key("angle_increment_rad", out), AppendShortestNumber(e.angle_increment_rad, out);
          Key("range_min_m", out), AppendShortestNumber(e.range_min_m, out);
          Key("range_max_m", out), AppendShortestNumber(e.range_max_m, out);
          Key("ranges_m", out);
          out += '[';
          for (std::size_t i = 0; i < e.ranges_m.size(); ++i) {
            if (i) out += ',';
            AppendShortestNumber(e.ranges_m[i], out);
          }
          out += ']';
          Key("valid", out);
          out += '[';
          for (std::size_t i = 0; i < e.valid.size(); ++i) {
            if (i) out += ',';
            out += e.valid[i] ? '1' : '0';
          }
          out += ']';
        } else if constexpr (std::is_same_v<E, LandmarkEvent>) {
          out += "{\"type\":\"landmarks\"";
          Key("t_s", out), AppendShortestNumber(e.t_s, out);
          Key("observations", out);
          out += '[';
          for (std::size_t i = 0; i < e.observations.size(); ++i) {
            const auto& o = e.observations[i];
            out += i ? ",{\"range_m\":" : "{\"range_m\":";
            AppendShortestNumber(o.range_m, out);
            Key("bearing_rad", out), AppendShortestNumber(o.bearing_rad, out);
            Key("id", out), AppendInt(o.id, out);
            out += '}';
          }
          out += ']';
        } else {
          out += "{\"type\":\"gyro\"";
          Key("t_s", out), AppendShortestNumber(e.t_s, out);
          Key("yaw_rate_rps", out), AppendShortestNumber(e.yaw_rate_rps, out);
        }
        out += "}\n";
      },
      event);
}

namespace {

struct LineContext {
  std::string_view line;
  long number;
  [[noreturn]] void Fail(const std::string& problem) const {
    const std::string_view shown = line.substr(0, 200);
    throw ExecProtocolError("stdout line " + std::to_string(number) + ": " + problem + ": " + std::string(shown) +
                            (line.size() > 200 ? "..." : ""));
  }
};

void CheckKeys(const json& j, std::initializer_list<const char*> required, std::initializer_list<const char*> optional,
               const LineContext& c) {
  for (const char* k : required)
    if (!j.contains(k)) c.Fail(std::string("missing key '") + k + "'");
  for (const auto& [key, value] : j.items()) {
    const auto is = [&](const char* k) { return key == k; };
    if (std::none_of(required.begin(), required.end(), is) && std::none_of(optional.begin(), optional.end(), is))
      c.Fail("unknown key '" + key + "'");
  }
}

/// A number, or NaN for the null that stands in for a bare NaN/Infinity token.
double Number(const json& j, const char* key, bool had_non_finite, const LineContext& c) {
  const json& v = j.at(key);
  if (v.is_number()) return v.get<double>();
  if (v.is_null() && had_non_finite) return std::nan("");
  c.Fail(std::string("'") + key + "' must be a number");
}

template <int N>
void Matrix(const json& j, double* out, bool had_non_finite, const LineContext& c) {
  const json& v = j.at("covariance");
  if (!v.is_array() || v.size() != N) c.Fail("'covariance' must be an array of " + std::to_string(N) + " numbers");
  for (int i = 0; i < N; ++i) {
    if (v[i].is_number()) out[i] = v[i].get<double>();
    else if (v[i].is_null() && had_non_finite) out[i] = std::nan("");
    else c.Fail("'covariance' must be an array of " + std::to_string(N) + " numbers");
  }
}

/// Python's json writes NaN and ±Infinity as bare tokens, which are not JSON. To tell a
/// diverged module from a garbled line, a line that does not parse is retried with those
/// tokens read as null.
std::string NonFiniteAsNull(std::string_view line) {
  std::string s(line);
  for (const char* token : {"-Infinity", "Infinity", "NaN"}) {
    const std::string t(token);
    for (std::size_t at = s.find(t); at != std::string::npos; at = s.find(t, at)) s.replace(at, t.size(), "null");
  }
  return s;
}

}  // namespace

void ExecAnswerParser::ParseLine(std::string_view line, long line_number, double latest_event_t_s) {
  const LineContext c{line, line_number};
  if (done_) c.Fail("output after {\"type\":\"done\"}");
  bool non_finite = false;
  json j = json::parse(line.begin(), line.end(), nullptr, false);
  if (j.is_discarded()) {
    j = json::parse(NonFiniteAsNull(line), nullptr, false);
    if (j.is_discarded()) c.Fail("not a JSON object");
    non_finite = true;
  }
  if (!j.is_object() || !j.contains("type") || !j["type"].is_string()) c.Fail("expected an object with a string 'type'");
  const std::string type = j["type"].get<std::string>();
  const auto diverged = [&](const std::string& what) {
    throw ModuleDiverged("stdout line " + std::to_string(line_number) + ": non-finite " + what);
  };
  if (type == "pose") {
    CheckKeys(j, {"type", "t_s", "x_m", "y_m", "theta_rad"}, {"covariance"}, c);
    PoseEstimate p;
    p.t_s = Number(j, "t_s", false, c);
    if (!std::isfinite(p.t_s)) c.Fail("'t_s' must be finite");
    if (!estimate_.trajectory.empty() && !(p.t_s > estimate_.trajectory.back().t_s))
      c.Fail("pose times must increase strictly");
    if (p.t_s > latest_event_t_s) c.Fail("a pose later than the last event sent");
    const double x = Number(j, "x_m", non_finite, c), y = Number(j, "y_m", non_finite, c),
                 theta = Number(j, "theta_rad", non_finite, c);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(theta)) diverged("pose");
    p.pose = SE2(x, y, theta);
    if (j.contains("covariance")) {
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> row_major;
      Matrix<9>(j, row_major.data(), non_finite, c);
      p.covariance = row_major;
      if (!p.covariance.allFinite()) diverged("pose covariance");
      p.has_covariance = true;
    }
    estimate_.trajectory.push_back(p);
  } else if (type == "landmark") {
    CheckKeys(j, {"type", "id", "x_m", "y_m"}, {"covariance"}, c);
    if (!j["id"].is_number_integer()) c.Fail("'id' must be an integer");
    LandmarkEstimate l;
    l.id = j["id"].get<int>();
    const auto at = std::lower_bound(landmark_ids_.begin(), landmark_ids_.end(), l.id);
    if (at != landmark_ids_.end() && *at == l.id) c.Fail("duplicate landmark id " + std::to_string(l.id));
    landmark_ids_.insert(at, l.id);
    l.position = {Number(j, "x_m", non_finite, c), Number(j, "y_m", non_finite, c)};
    if (!l.position.allFinite()) diverged("landmark position");
    if (j.contains("covariance")) {
      Eigen::Matrix<double, 2, 2, Eigen::RowMajor> row_major;
      Matrix<4>(j, row_major.data(), non_finite, c);
      l.covariance = row_major;
      if (!l.covariance.allFinite()) diverged("landmark covariance");
      l.has_covariance = true;
    }
    estimate_.landmarks.push_back(l);
  } else if (type == "diagnostic") {
    CheckKeys(j, {"type", "name", "t_s", "value"}, {}, c);
    if (!j["name"].is_string()) c.Fail("'name' must be a string");
    estimate_.diagnostics[j["name"].get<std::string>()].emplace_back(Number(j, "t_s", false, c),
                                                                      Number(j, "value", non_finite, c));
  } else if (type == "done") {
    CheckKeys(j, {"type"}, {}, c);
    done_ = true;
  } else {
    c.Fail("unknown type '" + type + "' (expected pose, landmark, diagnostic or done)");
  }
}

}  // namespace slambox
