#include "core/exec_protocol.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>

#include "core/error.hpp"
#include "core/flat_json.hpp"
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
  if (header.time_origin_s) j["time_origin_s"] = *header.time_origin_s;  // a converted log's own clock at t_s = 0
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

void CheckKeys(const FlatObject& j, std::initializer_list<const char*> required,
               std::initializer_list<const char*> optional, const LineContext& c) {
  for (const char* k : required)
    if (!j.Find(k)) c.Fail(std::string("missing key '") + k + "'");
  for (const auto& member : j.members) {
    const auto& key = member.first;  // not a structured binding: clang 14 cannot capture one
    const auto is = [&](const char* k) { return key == k; };
    if (std::none_of(required.begin(), required.end(), is) && std::none_of(optional.begin(), optional.end(), is))
      c.Fail("unknown key '" + key + "'");
  }
}

/// A number (a NaN/Infinity token reads as non-finite: the caller decides between failed
/// and diverged).
double Number(const FlatObject& j, const char* key, const LineContext& c) {
  const FlatValue& v = *j.Find(key);
  if (v.kind != FlatValue::Kind::kNumber) c.Fail(std::string("'") + key + "' must be a number");
  return v.number;
}

template <int N>
void Matrix(const FlatObject& j, double* out, const LineContext& c) {
  const FlatValue& v = *j.Find("covariance");
  if (v.kind != FlatValue::Kind::kNumberArray || v.numbers.size() != N)
    c.Fail("'covariance' must be an array of " + std::to_string(N) + " numbers");
  std::copy(v.numbers.begin(), v.numbers.end(), out);
}

}  // namespace

void ExecAnswerParser::ParseLine(std::string_view line, long line_number, double latest_event_t_s) {
  const LineContext c{line, line_number};
  if (done_) c.Fail("output after {\"type\":\"done\"}");
  FlatObject& j = object_;
  if (const std::string error = ParseFlatObject(line, j); !error.empty()) c.Fail("not a JSON object (" + error + ")");
  const FlatValue* type_value = j.Find("type");
  if (!type_value || type_value->kind != FlatValue::Kind::kString) c.Fail("expected an object with a string 'type'");
  const std::string& type = type_value->text;
  const auto diverged = [&](const std::string& what) {
    throw ModuleDiverged("stdout line " + std::to_string(line_number) + ": non-finite " + what);
  };
  if (type == "pose") {
    CheckKeys(j, {"type", "t_s", "x_m", "y_m", "theta_rad"}, {"covariance"}, c);
    PoseEstimate p;
    p.t_s = Number(j, "t_s", c);
    if (!std::isfinite(p.t_s)) c.Fail("'t_s' must be finite");
    if (!estimate_.trajectory.empty() && !(p.t_s > estimate_.trajectory.back().t_s))
      c.Fail("pose times must increase strictly");
    if (p.t_s > latest_event_t_s) c.Fail("a pose later than the last event sent");
    const double x = Number(j, "x_m", c), y = Number(j, "y_m", c), theta = Number(j, "theta_rad", c);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(theta)) diverged("pose");
    p.pose = SE2(x, y, theta);
    if (j.Find("covariance")) {
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> row_major;
      Matrix<9>(j, row_major.data(), c);
      p.covariance = row_major;
      if (!p.covariance.allFinite()) diverged("pose covariance");
      p.has_covariance = true;
    }
    estimate_.trajectory.push_back(p);
  } else if (type == "landmark") {
    CheckKeys(j, {"type", "id", "x_m", "y_m"}, {"covariance"}, c);
    const FlatValue& id = *j.Find("id");
    if (id.kind != FlatValue::Kind::kNumber || !id.integer || std::abs(id.number) > 2147483647.0)
      c.Fail("'id' must be an integer");
    LandmarkEstimate l;
    l.id = static_cast<int>(id.number);
    const auto at = std::lower_bound(landmark_ids_.begin(), landmark_ids_.end(), l.id);
    if (at != landmark_ids_.end() && *at == l.id) c.Fail("duplicate landmark id " + std::to_string(l.id));
    landmark_ids_.insert(at, l.id);
    l.position = {Number(j, "x_m", c), Number(j, "y_m", c)};
    if (!l.position.allFinite()) diverged("landmark position");
    if (j.Find("covariance")) {
      Eigen::Matrix<double, 2, 2, Eigen::RowMajor> row_major;
      Matrix<4>(j, row_major.data(), c);
      l.covariance = row_major;
      if (!l.covariance.allFinite()) diverged("landmark covariance");
      l.has_covariance = true;
    }
    estimate_.landmarks.push_back(l);
  } else if (type == "diagnostic") {
    CheckKeys(j, {"type", "name", "t_s", "value"}, {}, c);
    const FlatValue& name = *j.Find("name");
    if (name.kind != FlatValue::Kind::kString) c.Fail("'name' must be a string");
    const double t_s = Number(j, "t_s", c);
    if (!std::isfinite(t_s)) c.Fail("'t_s' must be finite");
    estimate_.diagnostics[name.text].emplace_back(t_s, Number(j, "value", c));
  } else if (type == "assignment") {  // optional (added with association_agreement): older children never send it
    CheckKeys(j, {"type", "scan", "index", "landmark"}, {"created"}, c);
    const auto integer = [&](const char* key, double min) {
      const FlatValue& v = *j.Find(key);
      if (v.kind != FlatValue::Kind::kNumber || !v.integer || v.number < min || v.number > 2147483647.0)
        c.Fail(std::string("'") + key + "' must be an integer >= " + std::to_string(static_cast<int>(min)));
      return static_cast<int>(v.number);
    };
    ObservationAssignment a{integer("scan", 0), integer("index", 0), integer("landmark", -1), false};
    if (const FlatValue* created = j.Find("created")) {
      if (created->kind != FlatValue::Kind::kBool) c.Fail("'created' must be true or false");
      a.created = created->boolean;
    }
    estimate_.observation_assignments.push_back(a);
  } else if (type == "done") {
    CheckKeys(j, {"type"}, {}, c);
    done_ = true;
  } else {
    c.Fail("unknown type '" + type + "' (expected pose, landmark, diagnostic, assignment or done)");
  }
}

}  // namespace slambox
