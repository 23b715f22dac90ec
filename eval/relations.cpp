#include "eval/relations.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/limits.hpp"

namespace slambox {

namespace {
constexpr const char* kFix = "each line is `t_i t_j dx dy dz roll pitch dtheta` (Kümmerle et al. 2009 relation files)";

// Index of the pose nearest to t within the tolerance, or -1 (ties: the earlier pose).
int NearestPose(const std::vector<StampedPose>& trajectory, double t, double max_diff) {
  const auto it = std::lower_bound(trajectory.begin(), trajectory.end(), t,
                                   [](const StampedPose& p, double v) { return p.t_s < v; });
  const int k = static_cast<int>(it - trajectory.begin());
  int best = -1;
  for (int j : {k - 1, k})
    if (j >= 0 && j < static_cast<int>(trajectory.size()) &&
        (best < 0 || std::abs(trajectory[j].t_s - t) < std::abs(trajectory[best].t_s - t)))
      best = j;
  return best >= 0 && std::abs(trajectory[best].t_s - t) <= max_diff ? best : -1;
}
}  // namespace

std::vector<Relation> ParseRelations(const std::string& text, const std::string& name) {
  std::vector<Relation> out;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    limits::CheckLineLength(name, number, line.size());
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string t; fields >> t;) tokens.push_back(t);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    if (tokens.size() < 8)
      throw InputError(name, number, "expected 8 numbers, found " + std::to_string(tokens.size()), kFix);
    double v[8];
    for (int i = 0; i < 8; ++i) {
      char* end = nullptr;
      v[i] = std::strtod(tokens[i].c_str(), &end);
      if (end == tokens[i].c_str() || *end != '\0' || !std::isfinite(v[i]))
        throw InputError(name, number, "field " + std::to_string(i + 1) + " is '" + tokens[i] + "', not a finite number",
                         kFix);
    }
    // Bounds as every reader has them (core/limits.hpp): a finite 1e308 would overflow the
    // relation's error to infinity (found by tests/fuzz/fuzz_relations).
    const auto out_of_range = [&](int i, double limit, const char* what) {
      if (std::abs(v[i]) > limit)
        throw InputError(name, number,
                         "field " + std::to_string(i + 1) + " = " + tokens[i] + " is out of range (" + what + " within ±" +
                             std::to_string(static_cast<long long>(limit)) + ")",
                         kFix);
    };
    out_of_range(0, limits::kMaxTimestampS, "times [s]");
    out_of_range(1, limits::kMaxTimestampS, "times [s]");
    for (int i = 2; i <= 4; ++i) out_of_range(i, limits::kMaxCoordinateM, "displacements [m]");
    for (int i = 5; i <= 7; ++i) out_of_range(i, limits::kMaxAngleRad, "angles [rad]");
    out.push_back({v[0], v[1], SE2(v[2], v[3], v[7]), number});
  }
  if (out.empty()) throw InputError(name, 0, "no relation in the file", kFix);
  return out;
}

std::vector<Relation> ReadRelations(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open the relations file", "check the path");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseRelations(text.str(), path);
}

RelationErrors ComputeRelationErrors(const std::vector<Relation>& relations, const std::vector<StampedPose>& trajectory,
                                     const RelationMatchOptions& o) {
  RelationErrors out;
  for (const Relation& r : relations) {
    const int i = NearestPose(trajectory, r.t_i_s - o.time_origin_s, o.max_time_diff_s);
    const int j = NearestPose(trajectory, r.t_j_s - o.time_origin_s, o.max_time_diff_s);
    if (i < 0 || j < 0) {
      ++out.unmatched;
      continue;
    }
    // Kümmerle et al. 2009 eq. 2: e = d_ref^-1 d_est, d_est = x_i^-1 x_j.
    const SE2 e = r.T_i_j.inverse() * Between(trajectory[i].pose, trajectory[j].pose);
    out.translation_m.push_back(e.translation().norm());
    out.rotation_deg.push_back(std::abs(NormalizeAngle(e.theta)) * 180.0 / M_PI);
  }
  return out;
}

int RelationsWithin(const std::vector<Relation>& relations, double duration_s, const RelationMatchOptions& o) {
  const auto inside = [&](double t) {
    const double s = t - o.time_origin_s;
    return s >= -o.max_time_diff_s && s <= duration_s + o.max_time_diff_s;
  };
  return static_cast<int>(std::count_if(relations.begin(), relations.end(),
                                        [&](const Relation& r) { return inside(r.t_i_s) && inside(r.t_j_s); }));
}

}  // namespace slambox
