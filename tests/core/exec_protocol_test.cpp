// The exec protocol's text (docs/exec_protocol.md): event lines round-trip bit for bit,
// and the child's answers are validated strictly, with the line number in every error.
#include "core/exec_protocol.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/error.hpp"

namespace slambox {
namespace {

using nlohmann::json;

std::uint64_t Bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

TEST(ExecProtocol, NumbersRoundTripBitForBitAndReadAsFloats) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-30.0, 30.0);
  for (int i = 0; i < 20000; ++i) {
    const double v = u(rng) * std::pow(10.0, e(rng));
    std::string s;
    AppendShortestNumber(v, s);
    EXPECT_EQ(Bits(json::parse(s).get<double>()), Bits(v)) << s;
    EXPECT_TRUE(json::parse(s).is_number_float()) << s;
  }
  for (double v : {0.0, 1.0, -3.0, 1e22, 123456789.0}) {
    std::string s;
    AppendShortestNumber(v, s);
    EXPECT_TRUE(json::parse(s).is_number_float()) << s;  // "1.0", never "1": Python reads a float
    EXPECT_EQ(json::parse(s).get<double>(), v);
  }
  std::string s;
  AppendShortestNumber(std::nan(""), s);
  EXPECT_EQ(s, "null");
}

TEST(ExecProtocol, EventLinesCarryEveryFieldExactly) {
  std::string out;
  AppendEventLine(OdometryEvent{0.02, SE2(0.1, -1e-7, 0.3)}, out);
  LaserScanEvent scan{0.1, -M_PI, 0.5, 0.1, 30.0, {1.25, 30.0}, {1, 0}};
  AppendEventLine(scan, out);
  AppendEventLine(LandmarkEvent{0.1, {{4.5, -0.25, 7}, {2.0, 1.0, -1}}}, out);
  AppendEventLine(GyroEvent{0.01, -0.002}, out);
  std::vector<json> lines;
  for (std::size_t at = 0, nl; (nl = out.find('\n', at)) != std::string::npos; at = nl + 1)
    lines.push_back(json::parse(out.substr(at, nl - at)));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], json::parse(R"({"type":"odometry","t_s":0.02,"dx_m":0.1,"dy_m":-1e-7,"dtheta_rad":0.3})"));
  EXPECT_EQ(lines[1]["type"], "scan");
  EXPECT_EQ(lines[1]["angle_min_rad"].get<double>(), -M_PI);
  EXPECT_EQ(lines[1]["ranges_m"], json::parse("[1.25, 30.0]"));
  EXPECT_EQ(lines[1]["valid"], json::parse("[1, 0]"));
  EXPECT_EQ(lines[2]["observations"][0], json::parse(R"({"range_m":4.5,"bearing_rad":-0.25,"id":7})"));
  EXPECT_EQ(lines[2]["observations"][1]["id"], -1);
  EXPECT_EQ(lines[3], json::parse(R"({"type":"gyro","t_s":0.01,"yaw_rate_rps":-0.002})"));
}

TEST(ExecProtocol, HeaderHasVersionParamsAndTheWorldOnlyWhenAsked) {
  StreamHeader h;
  h.scenario_name = "loop";
  h.start_pose = SE2(1.0, 2.0, 0.5);
  h.sensors.odometry = OdometryConfig{};
  h.world.wall_segments.push_back(Segment{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0)});
  const json j = json::parse(ExecHeaderLine(h, "exec:x", json{{"k", 2.5}}, false));
  EXPECT_EQ(j["type"], "header");
  EXPECT_EQ(j["protocol"], "slambox-exec");
  EXPECT_EQ(j["version"], kExecProtocolVersion);
  EXPECT_EQ(j["module"], "exec:x");
  EXPECT_EQ(j["params"]["k"], 2.5);
  EXPECT_EQ(j["start_pose"], json::parse("[1.0, 2.0, 0.5]"));
  EXPECT_EQ(j["sensors"]["odometry"]["alpha"].size(), 4u);
  EXPECT_FALSE(j.contains("world"));
  EXPECT_FALSE(j.contains("time_origin_s"));
  h.time_origin_s = 1000.25;
  EXPECT_EQ(json::parse(ExecHeaderLine(h, "exec:x", json::object(), false))["time_origin_s"], 1000.25);
  EXPECT_TRUE(json::parse(ExecHeaderLine(h, "exec:x", json::object(), true)).contains("world"));
  const json exported = json::parse(ExecHeaderLine(h, "", nullptr, true));
  EXPECT_FALSE(exported.contains("module"));
  EXPECT_FALSE(exported.contains("params"));
}

TEST(ExecProtocol, ParsesPosesLandmarksDiagnosticsAndDone) {
  ExecAnswerParser p;
  p.ParseLine(R"({"type":"pose","t_s":0.0,"x_m":1.0,"y_m":2.0,"theta_rad":4.0})", 1, 0.0);
  p.ParseLine(R"({"type":"pose","t_s":0.5,"x_m":1.5,"y_m":2.0,"theta_rad":0.1,"covariance":[1,2,3,4,5,6,7,8,9]})", 2, 1.0);
  p.ParseLine(R"({"type":"landmark","id":3,"x_m":4.0,"y_m":5.0,"covariance":[1,2,3,4]})", 3, 1.0);
  p.ParseLine(R"({"type":"diagnostic","name":"iters","t_s":0.5,"value":7})", 4, 1.0);
  p.ParseLine(R"({"type":"done"})", 5, 1.0);
  EXPECT_TRUE(p.done());
  const Estimate e = p.TakeEstimate();
  ASSERT_EQ(e.trajectory.size(), 2u);
  EXPECT_FALSE(e.trajectory[0].has_covariance);
  EXPECT_NEAR(e.trajectory[0].pose.theta, 4.0 - 2 * M_PI, 1e-15);  // wrapped into [-pi, pi)
  EXPECT_TRUE(e.trajectory[1].has_covariance);
  EXPECT_EQ(e.trajectory[1].covariance(0, 1), 2.0);  // row-major
  EXPECT_EQ(e.trajectory[1].covariance(1, 0), 4.0);
  ASSERT_EQ(e.landmarks.size(), 1u);
  EXPECT_EQ(e.landmarks[0].id, 3);
  EXPECT_EQ(e.landmarks[0].covariance(0, 1), 2.0);
  EXPECT_EQ(e.diagnostics.at("iters").at(0).second, 7.0);
}

TEST(ExecProtocol, ParsesOptionalAssignments) {
  ExecAnswerParser p;
  p.ParseLine(R"({"type":"assignment","scan":0,"index":1,"landmark":4,"created":true})", 1, 1.0);
  p.ParseLine(R"({"type":"assignment","scan":2,"index":0,"landmark":-1})", 2, 1.0);
  p.ParseLine(R"({"type":"done"})", 3, 1.0);
  const Estimate e = p.TakeEstimate();
  ASSERT_EQ(e.observation_assignments.size(), 2u);
  EXPECT_EQ(e.observation_assignments[0].scan, 0);
  EXPECT_EQ(e.observation_assignments[0].index, 1);
  EXPECT_EQ(e.observation_assignments[0].landmark, 4);
  EXPECT_TRUE(e.observation_assignments[0].created);
  EXPECT_EQ(e.observation_assignments[1].landmark, -1);
  EXPECT_FALSE(e.observation_assignments[1].created);
}

std::string ErrorOf(const std::vector<std::string>& lines, double latest_t_s = 10.0) {
  ExecAnswerParser p;
  try {
    for (std::size_t i = 0; i < lines.size(); ++i) p.ParseLine(lines[i], static_cast<long>(i + 1), latest_t_s);
  } catch (const ExecProtocolError& e) {
    return std::string("failed: ") + e.what();
  } catch (const ModuleDiverged& e) {
    return std::string("diverged: ") + e.what();
  }
  return "accepted";
}

TEST(ExecProtocol, RejectsEveryBrokenAnswerNamingTheLine) {
  const std::string pose = R"({"type":"pose","t_s":1.0,"x_m":0.0,"y_m":0.0,"theta_rad":0.0})";
  const auto failed = [](const std::string& what, const std::string& needle) {
    EXPECT_EQ(what.rfind("failed: stdout line 2: ", 0), 0u) << what;
    EXPECT_NE(what.find(needle), std::string::npos) << what;
  };
  failed(ErrorOf({pose, "hello"}), "not a JSON object");
  failed(ErrorOf({pose, "[1,2]"}), "expected '{'");
  failed(ErrorOf({pose, R"({"x_m":1.0})"}), "string 'type'");
  failed(ErrorOf({pose, R"({"type":"pose","t_s":2.0,"x_m":0.0,"y_m":0.0,"theta_rad":0} trailing)"}), "text after");
  failed(ErrorOf({pose, R"({"type":"posture"})"}), "unknown type 'posture'");
  failed(ErrorOf({pose, R"({"type":"assignment","scan":-1,"index":0,"landmark":2})"}), "'scan' must be an integer");
  failed(ErrorOf({pose, R"({"type":"assignment","scan":1,"index":0.5,"landmark":2})"}), "'index' must be an integer");
  failed(ErrorOf({pose, R"({"type":"assignment","scan":1,"index":0,"landmark":-2})"}), "'landmark' must be an integer");
  failed(ErrorOf({pose, R"({"type":"assignment","scan":1,"index":0,"landmark":2,"created":1})"}), "'created' must be");
  failed(ErrorOf({pose, R"({"type":"pose","t_s":2.0,"x_m":0.0,"y_m":0.0})"}), "missing key 'theta_rad'");
  failed(ErrorOf({pose, R"({"type":"pose","t_s":2.0,"x_m":0.0,"y_m":0.0,"theta_rad":0,"z_m":1})"}), "unknown key 'z_m'");
  failed(ErrorOf({pose, R"({"type":"pose","t_s":2.0,"x_m":"0","y_m":0.0,"theta_rad":0})"}), "'x_m' must be a number");
  failed(ErrorOf({pose, pose}), "increase strictly");
  failed(ErrorOf({pose, R"({"type":"pose","t_s":11.0,"x_m":0.0,"y_m":0.0,"theta_rad":0})"}), "later than the last event");
  failed(ErrorOf({pose, R"({"type":"pose","t_s":2.0,"x_m":0.0,"y_m":0.0,"theta_rad":0,"covariance":[1,2]})"}),
         "array of 9");
  const std::string lm = R"({"type":"landmark","id":1,"x_m":0.0,"y_m":0.0})";
  failed(ErrorOf({lm, lm}), "duplicate landmark id 1");
  failed(ErrorOf({R"({"type":"done"})", pose}), "after");
  failed(ErrorOf({pose, R"({"type":"landmark","id":1.5,"x_m":0.0,"y_m":0.0})"}), "'id' must be an integer");
  EXPECT_EQ(ErrorOf({pose, R"({"type":"done"})"}), "accepted");
}

TEST(ExecProtocol, NonFiniteValuesAreDivergedNotGarbage) {
  const auto diverged = [](const std::string& what) {
    EXPECT_EQ(what.rfind("diverged: stdout line 1: non-finite", 0), 0u) << what;
  };
  diverged(ErrorOf({R"({"type":"pose","t_s":1.0,"x_m":NaN,"y_m":0.0,"theta_rad":0.0})"}));
  diverged(ErrorOf({R"({"type":"pose","t_s":1.0,"x_m":0.0,"y_m":-Infinity,"theta_rad":0.0})"}));
  diverged(ErrorOf({R"({"type":"pose","t_s":1.0,"x_m":0.0,"y_m":0.0,"theta_rad":0.0,"covariance":[1,0,0,0,Infinity,0,0,0,1]})"}));
  diverged(ErrorOf({R"({"type":"landmark","id":1,"x_m":NaN,"y_m":0.0})"}));
  // An explicit null is a wrong type, and a NaN time cannot be placed: both fail.
  EXPECT_EQ(ErrorOf({R"({"type":"pose","t_s":1.0,"x_m":null,"y_m":0.0,"theta_rad":0.0})"}).rfind("failed", 0), 0u);
  EXPECT_EQ(ErrorOf({R"({"type":"pose","t_s":NaN,"x_m":0.0,"y_m":0.0,"theta_rad":0.0})"}).rfind("failed", 0), 0u);
  EXPECT_EQ(ErrorOf({R"({"type":"diagnostic","name":"d","t_s":1.0,"value":NaN})"}), "accepted");
}

}  // namespace
}  // namespace slambox
