#include "slam/g2o_io.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/limits.hpp"
#include "slam/pose_graph_cost.hpp"

namespace slambox {
namespace {

struct RawVertex {
  SE2 pose;
  int line = 0;
};
struct RawEdge {
  long long from = 0, to = 0;
  PoseGraphEdge edge;
  int line = 0;
};

const char* kTagsFix =
    "use VERTEX_SE2, EDGE_SE2, FIX (g2o), VERTEX2, EDGE2 (TORO) or ODOMETRY (iSAM); '#' starts a comment";

class LineParser {
 public:
  LineParser(const std::string& file, int line, const std::vector<std::string>& tokens)
      : file_(file), line_(line), tag_(tokens[0]), tokens_(tokens) {}

  void ExpectCount(size_t count, const std::string& form) const {
    if (tokens_.size() != count)
      throw InputError(file_, line_,
                       tag_ + " has " + std::to_string(tokens_.size() - 1) + " values, expected " +
                           std::to_string(count - 1),
                       "write it as '" + form + "'");
  }
  double Number(size_t k) const {
    const std::string& s = tokens_[k];
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (end == s.c_str() || *end != '\0')
      throw InputError(file_, line_, tag_ + " value " + std::to_string(k) + " '" + s + "' is not a number",
                       "write a decimal number");
    if (!std::isfinite(v))
      throw InputError(file_, line_, tag_ + " value " + std::to_string(k) + " is " + s,
                       "replace it with a finite number");
    return v;
  }
  /// A position [m] within +-limits::kMaxCoordinateM.
  double Coordinate(size_t k) const { return Bounded(k, limits::kMaxCoordinateM, "a position in metres"); }
  /// An angle [rad] within +-limits::kMaxAngleRad.
  double Angle(size_t k) const { return Bounded(k, limits::kMaxAngleRad, "an angle in radians"); }
  double Bounded(size_t k, double bound, const char* what) const {
    const double v = Number(k);
    if (std::abs(v) > bound)
      throw InputError(file_, line_, tag_ + " value " + std::to_string(k) + " " + tokens_[k] + " is out of range for " + what,
                       "write a value within +-" + tokens_limit(bound) + " (core/limits.hpp)");
    return v;
  }
  static std::string tokens_limit(double bound) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", bound);
    return buf;
  }
  long long Id(size_t k) const {
    const std::string& s = tokens_[k];
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(s.c_str(), &end, 10);
    if (end == s.c_str() || *end != '\0' || errno == ERANGE || v < 0 || v > 2147483647LL)
      throw InputError(file_, line_, tag_ + " id '" + s + "' is not a non-negative integer",
                       "vertex ids are integers 0 .. 2147483647");
    return v;
  }

 private:
  const std::string& file_;
  int line_;
  const std::string& tag_;
  const std::vector<std::string>& tokens_;
};

void SplitWords(std::string_view line, std::vector<std::string>* words) {
  words->clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) words->emplace_back(line.substr(i, j - i));
    i = j;
  }
}

enum class EdgeFormat { kG2o, kToro, kIsam };

// Information over (dx, dy, dtheta) from the file's six values in g2o, TORO or iSAM order.
Eigen::Matrix3d Information(const LineParser& p, EdgeFormat format) {
  double xx, xy, xt, yy, yt, tt;
  if (format == EdgeFormat::kIsam) {  // sxx sxy sxt syy syt stt: square root R, Omega = R^T R
    Eigen::Matrix3d R;
    R << p.Number(6), p.Number(7), p.Number(8), 0.0, p.Number(9), p.Number(10), 0.0, 0.0, p.Number(11);
    return R.transpose() * R;
  }
  if (format == EdgeFormat::kToro) {  // inf_ff inf_fs inf_ss inf_rr inf_fr inf_sr
    xx = p.Number(6), xy = p.Number(7), yy = p.Number(8), tt = p.Number(9), xt = p.Number(10), yt = p.Number(11);
  } else {  // I11 I12 I13 I22 I23 I33
    xx = p.Number(6), xy = p.Number(7), xt = p.Number(8), yy = p.Number(9), yt = p.Number(10), tt = p.Number(11);
  }
  Eigen::Matrix3d I;
  I << xx, xy, xt, xy, yy, yt, xt, yt, tt;
  return I;
}

}  // namespace

PoseGraphFile ParsePoseGraph(const std::string& text, const std::string& name) {
  std::map<long long, RawVertex> vertices;
  std::vector<RawEdge> edges;
  std::vector<std::pair<long long, int>> fixed_ids;
  // iSAM files (ODOMETRY lines) give square-root information, also on their EDGE2 lines.
  const bool isam = text.rfind("ODOMETRY", 0) == 0 || text.find("\nODOMETRY") != std::string::npos;
  int line = 0;
  std::vector<std::string> tokens;
  for (size_t pos = 0; pos < text.size();) {
    ++line;
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    limits::CheckLineLength(name, line, end - pos);
    SplitWords(std::string_view(text).substr(pos, end - pos), &tokens);
    pos = end + 1;
    if (tokens.empty() || tokens[0][0] == '#') continue;
    const std::string& tag = tokens[0];
    LineParser p(name, line, tokens);
    if (tag == "VERTEX_SE2" || tag == "VERTEX2") {
      p.ExpectCount(5, tag + " id x y theta");
      const long long id = p.Id(1);
      if (vertices.count(id))
        throw InputError(name, line, "vertex " + std::to_string(id) + " is defined twice (first on line " +
                                         std::to_string(vertices[id].line) + ")",
                         "give each vertex one line");
      vertices[id] = {SE2(p.Coordinate(2), p.Coordinate(3), p.Angle(4)), line};
    } else if (tag == "EDGE_SE2" || tag == "EDGE2" || tag == "ODOMETRY") {
      const EdgeFormat format = tag == "EDGE_SE2"              ? EdgeFormat::kG2o
                                : (tag == "ODOMETRY" || isam) ? EdgeFormat::kIsam
                                                              : EdgeFormat::kToro;
      const std::string values = format == EdgeFormat::kG2o    ? "I11 I12 I13 I22 I23 I33"
                                 : format == EdgeFormat::kToro ? "inf_ff inf_fs inf_ss inf_rr inf_fr inf_sr"
                                                               : "sxx sxy sxt syy syt stt";
      p.ExpectCount(12, tag + " i j dx dy dtheta " + values);
      RawEdge e;
      e.from = p.Id(1);
      e.to = p.Id(2);
      e.line = line;
      if (e.from == e.to)
        throw InputError(name, line, "edge joins vertex " + std::to_string(e.from) + " to itself",
                         "remove the line or fix its ids");
      e.edge.T_from_to = SE2(p.Coordinate(3), p.Coordinate(4), p.Angle(5));
      e.edge.information = Information(p, format);
      Eigen::Matrix3d U;
      if (!SqrtInformation(e.edge.information, &U))
        throw InputError(name, line, "edge information matrix is not positive definite",
                         format == EdgeFormat::kIsam
                             ? "give an upper-triangular square-root information (" + values + ") with a nonzero diagonal"
                             : "give the upper triangle of a positive definite information matrix (" + values + ")");
      edges.push_back(e);
    } else if (tag == "FIX") {
      if (tokens.size() < 2) throw InputError(name, line, "FIX names no vertex", "write 'FIX id'");
      for (size_t k = 1; k < tokens.size(); ++k) fixed_ids.push_back({p.Id(k), line});
    } else {
      throw InputError(name, line, "unknown tag '" + tag + "'", kTagsFix);
    }
  }

  PoseGraphFile file;
  file.has_initial_guess = !vertices.empty();
  if (vertices.empty()) {  // edges only: vertices are whatever the edges name
    for (const RawEdge& e : edges) {
      vertices.emplace(e.from, RawVertex{SE2(), e.line});
      vertices.emplace(e.to, RawVertex{SE2(), e.line});
    }
  }
  if (vertices.empty()) throw InputError(name, 0, "no vertices or edges found", "is this a g2o or TORO 2D graph?");
  std::map<long long, int> index;
  for (const auto& [id, v] : vertices) {
    index[id] = static_cast<int>(file.vertex_ids.size());
    file.vertex_ids.push_back(static_cast<int>(id));
    file.graph.poses.push_back(v.pose);
  }
  for (const RawEdge& e : edges) {
    for (long long id : {e.from, e.to})
      if (!index.count(id))
        throw InputError(name, e.line, "edge names vertex " + std::to_string(id) + ", which has no VERTEX line",
                         "add 'VERTEX_SE2 " + std::to_string(id) + " x y theta' or remove the edge");
    PoseGraphEdge edge = e.edge;
    edge.from = index[e.from];
    edge.to = index[e.to];
    edge.loop_closure = std::abs(edge.to - edge.from) != 1;
    file.graph.edges.push_back(edge);
  }
  for (const auto& [id, fix_line] : fixed_ids) {
    if (!index.count(id))
      throw InputError(name, fix_line, "FIX names vertex " + std::to_string(id) + ", which does not exist",
                       "fix an existing vertex id");
    file.fixed.push_back(index[id]);
  }
  file.graph.anchor = file.fixed.empty() ? 0 : file.fixed.front();
  return file;
}

PoseGraphFile ReadPoseGraph(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the pose graph file", "check the path and permissions");
  std::ostringstream text;
  text << in.rdbuf();
  return ParsePoseGraph(text.str(), path);
}

std::string FormatPoseGraph(const PoseGraph& graph, const std::vector<int>& vertex_ids) {
  auto id = [&](int i) { return vertex_ids.empty() ? i : vertex_ids.at(i); };
  std::string out;
  char buf[512];
  for (size_t i = 0; i < graph.poses.size(); ++i) {
    const SE2& p = graph.poses[i];
    std::snprintf(buf, sizeof buf, "VERTEX_SE2 %d %.17g %.17g %.17g\n", id(static_cast<int>(i)), p.x, p.y, p.theta);
    out += buf;
  }
  if (!graph.poses.empty()) {
    std::snprintf(buf, sizeof buf, "FIX %d\n", id(graph.anchor));
    out += buf;
  }
  for (const PoseGraphEdge& e : graph.edges) {
    const Eigen::Matrix3d& I = e.information;
    std::snprintf(buf, sizeof buf,
                  "EDGE_SE2 %d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", id(e.from),
                  id(e.to), e.T_from_to.x, e.T_from_to.y, e.T_from_to.theta, I(0, 0), I(0, 1), I(0, 2), I(1, 1),
                  I(1, 2), I(2, 2));
    out += buf;
  }
  return out;
}

void WritePoseGraph(const std::string& path, const PoseGraph& graph, const std::vector<int>& vertex_ids) {
  WriteFileAtomic(path, FormatPoseGraph(graph, vertex_ids));
}

}  // namespace slambox
