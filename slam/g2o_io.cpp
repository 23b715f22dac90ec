#include "slam/g2o_io.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "slam/landmark_edge_cost.hpp"
#include "slam/pose_graph_cost.hpp"

namespace slambox {
namespace {

enum class NodeKind { kPose, kLandmark };
struct RawVertex {
  NodeKind kind = NodeKind::kPose;
  SE2 pose;               ///< kPose
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< kLandmark
  int line = 0;
};
struct RawEdge {
  long long from = 0, to = 0;
  PoseGraphEdge edge;
  int line = 0;
};
struct RawLandmarkEdge {
  long long pose = 0, landmark = 0;
  LandmarkEdge edge;
  int line = 0;
  bool isam = false;  ///< LANDMARK: the landmark id is iSAM's own namespace, not a vertex id
};

const char* kTagsFix =
    "use VERTEX_SE2, VERTEX_XY, EDGE_SE2, EDGE_SE2_XY, FIX (g2o), VERTEX2, EDGE2 (TORO) or ODOMETRY, EDGE2, "
    "LANDMARK (iSAM); '#' starts a comment";

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

std::string_view FirstWord(std::string_view line) {
  size_t i = 0;
  while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
  size_t j = i;
  while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
  return line.substr(i, j - i);
}

bool HasIsamLines(std::string_view text) {
  for (size_t pos = 0; pos < text.size();) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view word = FirstWord(text.substr(pos, end - pos));
    if (word == "ODOMETRY" || word == "LANDMARK") return true;
    pos = end + 1;
  }
  return false;
}

// The 2x2 information of a landmark edge: g2o's upper triangle I11 I12 I22, or an iSAM-
// family line's three values (slam/isam_noise.hpp). nullopt: not positive definite.
std::optional<Eigen::Matrix2d> PointInformation(const LineParser& p, std::optional<IsamNoise> isam) {
  const double v[3] = {p.Number(5), p.Number(6), p.Number(7)};
  if (isam) return IsamPointInformation(v, *isam);
  Eigen::Matrix2d M;
  M << v[0], v[1], v[1], v[2];
  return M;
}

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

// Information over (dx, dy, dtheta) from the file's six values in g2o or TORO order, or an
// iSAM-family line's (slam/isam_noise.hpp; nullopt: not positive definite).
std::optional<Eigen::Matrix3d> Information(const LineParser& p, EdgeFormat format, IsamNoise isam_noise) {
  double xx, xy, xt, yy, yt, tt;
  if (format == EdgeFormat::kIsam) {  // xx xy xt yy yt tt
    const double v[6] = {p.Number(6), p.Number(7), p.Number(8), p.Number(9), p.Number(10), p.Number(11)};
    return IsamPoseInformation(v, isam_noise);
  }
  if (format == EdgeFormat::kToro) {  // inf_ff inf_fs inf_ss inf_rr inf_fr inf_sr
    xx = p.Number(6), xy = p.Number(7), yy = p.Number(8), tt = p.Number(9), xt = p.Number(10), yt = p.Number(11);
  } else {  // I11 I12 I13 I22 I23 I33
    xx = p.Number(6), xy = p.Number(7), xt = p.Number(8), yy = p.Number(9), yt = p.Number(10), tt = p.Number(11);
  }
  // Values read before the comma initializer: a throw inside one trips its destructor's assert.
  Eigen::Matrix3d I;
  I << xx, xy, xt, xy, yy, yt, xt, yt, tt;
  return I;
}

}  // namespace

PoseGraphFile ParsePoseGraph(const std::string& text, const std::string& name, const PoseGraphReadOptions& options) {
  std::map<long long, RawVertex> vertices;
  std::vector<RawEdge> edges;
  std::vector<std::pair<long long, int>> fixed_ids;
  // iSAM files (any ODOMETRY or LANDMARK line, wherever it is) give square-root
  // information, also on their EDGE2 lines (iSAM's loader reads EDGE2 as ODOMETRY).
  const bool isam = HasIsamLines(text);
  const std::optional<IsamNoise> isam_noise = ResolveIsamNoise(text, name, options.isam_noise, isam);
  const IsamNoise noise = isam_noise.value_or(IsamNoise::kSqrtInformation);
  const bool covariance = noise == IsamNoise::kCovariance;
  std::vector<RawLandmarkEdge> landmark_edges;
  std::map<long long, int> isam_landmarks;  // iSAM landmark id -> first line naming it
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
    if (tag == "VERTEX_SE2" || tag == "VERTEX2" || tag == "VERTEX_XY") {
      const bool point = tag == "VERTEX_XY";
      p.ExpectCount(point ? 4 : 5, tag + (point ? " id x y" : " id x y theta"));
      const long long id = p.Id(1);
      if (vertices.count(id))
        throw InputError(name, line, "vertex " + std::to_string(id) + " is defined twice (first on line " +
                                         std::to_string(vertices[id].line) + ")",
                         "give each vertex one line (poses and points share one id space)");
      RawVertex v{point ? NodeKind::kLandmark : NodeKind::kPose, SE2(), Eigen::Vector2d::Zero(), line};
      if (point) v.point = Eigen::Vector2d(p.Coordinate(2), p.Coordinate(3));
      else v.pose = SE2(p.Coordinate(2), p.Coordinate(3), p.Angle(4));
      vertices[id] = v;
    } else if (tag == "EDGE_SE2_XY" || tag == "LANDMARK") {
      const bool sqrt_info = tag == "LANDMARK";  // iSAM's namespace and noise convention
      p.ExpectCount(8, tag + " pose_id point_id dx dy " +
                           (!sqrt_info ? "I11 I12 I22" : covariance ? "cxx cxy cyy" : "sxx sxy syy"));
      RawLandmarkEdge e;
      e.pose = p.Id(1);
      e.landmark = p.Id(2);
      e.line = line;
      e.isam = sqrt_info;
      e.edge.p_pose_landmark = Eigen::Vector2d(p.Coordinate(3), p.Coordinate(4));
      const std::optional<Eigen::Matrix2d> information =
          PointInformation(p, sqrt_info ? std::optional<IsamNoise>(noise) : std::nullopt);
      Eigen::Matrix2d U;
      if (!information || !SqrtInformation(*information, &U))
        throw InputError(name, line,
                         std::string("landmark edge ") + (sqrt_info && covariance ? "covariance" : "information") +
                             " matrix is not positive definite",
                         !sqrt_info   ? "give the upper triangle of a positive definite 2x2 information (I11 I12 I22)"
                         : covariance ? "give the upper triangle of a positive definite covariance (cxx cxy cyy)"
                                      : "give an upper-triangular square-root information (sxx sxy syy) with a nonzero diagonal");
      e.edge.information = *information;
      if (sqrt_info) isam_landmarks.emplace(e.landmark, line);
      landmark_edges.push_back(e);
    } else if (tag == "EDGE_SE2" || tag == "EDGE2" || tag == "ODOMETRY") {
      const EdgeFormat format = tag == "EDGE_SE2"              ? EdgeFormat::kG2o
                                : (tag == "ODOMETRY" || isam) ? EdgeFormat::kIsam
                                                              : EdgeFormat::kToro;
      const std::string values = format == EdgeFormat::kG2o    ? "I11 I12 I13 I22 I23 I33"
                                 : format == EdgeFormat::kToro ? "inf_ff inf_fs inf_ss inf_rr inf_fr inf_sr"
                                 : covariance                  ? "cxx cxy cxt cyy cyt ctt"
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
      const std::optional<Eigen::Matrix3d> information = Information(p, format, noise);
      Eigen::Matrix3d U;
      const bool cov = format == EdgeFormat::kIsam && covariance;
      if (!information || !SqrtInformation(*information, &U))
        throw InputError(name, line, std::string("edge ") + (cov ? "covariance" : "information") + " matrix is not positive definite",
                         cov ? "give the upper triangle of a positive definite covariance (" + values + ")"
                         : format == EdgeFormat::kIsam
                             ? "give an upper-triangular square-root information (" + values + ") with a nonzero diagonal"
                             : "give the upper triangle of a positive definite information matrix (" + values + ")");
      e.edge.information = *information;
      edges.push_back(e);
    } else if (tag == "FIX") {
      if (tokens.size() < 2) throw InputError(name, line, "FIX names no vertex", "write 'FIX id'");
      for (size_t k = 1; k < tokens.size(); ++k) fixed_ids.push_back({p.Id(k), line});
    } else {
      throw InputError(name, line, "unknown tag '" + tag + "'", kTagsFix);
    }
  }

  bool g2o_points = false;
  for (const auto& [id, v] : vertices) g2o_points = g2o_points || v.kind == NodeKind::kLandmark;
  for (const RawLandmarkEdge& e : landmark_edges) g2o_points = g2o_points || !e.isam;
  for (const RawLandmarkEdge& e : landmark_edges)
    if (g2o_points && e.isam)
      throw InputError(name, e.line, "the file mixes g2o points (VERTEX_XY / EDGE_SE2_XY) with iSAM LANDMARK lines",
                       "write landmarks in one format: g2o's (shared ids with poses) or iSAM's (own ids)");

  PoseGraphFile file;
  file.isam_noise = isam_noise;
  file.has_initial_guess = !vertices.empty() && isam_landmarks.empty();
  if (vertices.empty()) {  // edges only: vertices are whatever the edges name, of the kind they name
    for (const RawEdge& e : edges) {
      vertices.emplace(e.from, RawVertex{NodeKind::kPose, SE2(), Eigen::Vector2d::Zero(), e.line});
      vertices.emplace(e.to, RawVertex{NodeKind::kPose, SE2(), Eigen::Vector2d::Zero(), e.line});
    }
    for (const RawLandmarkEdge& e : landmark_edges) {
      vertices.emplace(e.pose, RawVertex{NodeKind::kPose, SE2(), Eigen::Vector2d::Zero(), e.line});
      if (!e.isam) vertices.emplace(e.landmark, RawVertex{NodeKind::kLandmark, SE2(), Eigen::Vector2d::Zero(), e.line});
    }
  }
  if (vertices.empty()) throw InputError(name, 0, "no vertices or edges found", "is this a g2o or TORO 2D graph?");
  std::map<long long, int> index, landmark_index;  // file id -> pose index / landmark index
  for (const auto& [id, v] : vertices) {
    if (v.kind == NodeKind::kLandmark) {
      landmark_index[id] = static_cast<int>(file.landmark_ids.size());
      file.landmark_ids.push_back(static_cast<int>(id));
      file.graph.landmarks.push_back(v.point);
      continue;
    }
    index[id] = static_cast<int>(file.vertex_ids.size());
    file.vertex_ids.push_back(static_cast<int>(id));
    file.graph.poses.push_back(v.pose);
  }
  for (const auto& [id, first_line] : isam_landmarks) {  // iSAM's own namespace, no initial guess
    landmark_index[id] = static_cast<int>(file.landmark_ids.size());
    file.landmark_ids.push_back(static_cast<int>(id));
    file.graph.landmarks.push_back(Eigen::Vector2d::Zero());
  }
  auto pose_of = [&](long long id, int edge_line, const std::string& tag) {
    const auto it = index.find(id);
    if (it != index.end()) return it->second;
    if (vertices.count(id))
      throw InputError(name, edge_line, tag + " names vertex " + std::to_string(id) + " as a pose, but it is a VERTEX_XY point",
                       "a pose end must be a VERTEX_SE2 pose; a point is observed with EDGE_SE2_XY pose_id point_id");
    throw InputError(name, edge_line, tag + " names vertex " + std::to_string(id) + ", which has no VERTEX line",
                     "add 'VERTEX_SE2 " + std::to_string(id) + " x y theta' or remove the edge");
  };
  for (const RawEdge& e : edges) {
    PoseGraphEdge edge = e.edge;
    edge.from = pose_of(e.from, e.line, "edge");
    edge.to = pose_of(e.to, e.line, "edge");
    edge.loop_closure = std::abs(edge.to - edge.from) != 1;
    file.graph.edges.push_back(edge);
  }
  for (const RawLandmarkEdge& e : landmark_edges) {
    LandmarkEdge edge = e.edge;
    const std::string tag = e.isam ? "LANDMARK" : "EDGE_SE2_XY";
    edge.pose = pose_of(e.pose, e.line, tag);
    const auto it = landmark_index.find(e.landmark);
    if (it == landmark_index.end()) {
      if (vertices.count(e.landmark))
        throw InputError(name, e.line, tag + " names vertex " + std::to_string(e.landmark) + " as its point, but it is a pose",
                         "the second id of EDGE_SE2_XY must be a VERTEX_XY point");
      throw InputError(name, e.line, tag + " names point " + std::to_string(e.landmark) + ", which has no VERTEX line",
                       "add 'VERTEX_XY " + std::to_string(e.landmark) + " x y' or remove the edge");
    }
    edge.landmark = it->second;
    file.graph.landmark_edges.push_back(edge);
  }
  for (const auto& [id, fix_line] : fixed_ids) {
    if (!index.count(id))
      throw InputError(name, fix_line,
                       "FIX names vertex " + std::to_string(id) + (vertices.count(id) ? ", a point" : ", which does not exist"),
                       "fix an existing pose (VERTEX_SE2) id: the fixed pose is the gauge");
    file.fixed.push_back(index[id]);
  }
  file.graph.anchor = file.fixed.empty() ? 0 : file.fixed.front();
  return file;
}

PoseGraphFile ReadPoseGraph(const std::string& path, const PoseGraphReadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the pose graph file", "check the path and permissions");
  std::ostringstream text;
  text << in.rdbuf();
  return ParsePoseGraph(text.str(), path, options);
}

}  // namespace slambox
