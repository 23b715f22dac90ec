#include "app/optimize_accuracy.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "eval/alignment.hpp"
#include "eval/ate.hpp"
#include "eval/landmark_map.hpp"
#include "eval/statistics.hpp"

namespace slambox {
namespace {

const char* kTruthForm =
    "write 'id x y theta' (a pose), 'id x y' (a landmark) or a g2o / TORO vertex line (VERTEX_SE2, VERTEX2, VERTEX_XY)";

double ParseNumber(const std::string& s, const std::string& path, int line) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0' || !std::isfinite(v))
    throw InputError(path, line, "'" + s + "' is not a finite number", kTruthForm);
  return v;
}

int ParseId(const std::string& s, const std::string& path, int line) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (end == s.c_str() || *end != '\0' || errno == ERANGE || v < 0 || v > 2147483647LL)
    throw InputError(path, line, "id '" + s + "' is not a non-negative integer", kTruthForm);
  return static_cast<int>(v);
}

template <typename T>
void Insert(std::map<int, T>& values, std::map<int, int>& lines, int id, const T& value, const char* kind,
            const std::string& path, int line) {
  if (lines.count(id))
    throw InputError(path, line,
                     std::string(kind) + " " + std::to_string(id) + " is given twice (first on line " +
                         std::to_string(lines[id]) + " of a ground-truth file)",
                     "give each true pose and landmark once");
  values[id] = value;
  lines[id] = line;
}

}  // namespace

void ReadVertexTruth(const std::string& path, VertexTruth* truth) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open the ground-truth file", "check the path and permissions");
  std::string text;
  size_t before = truth->poses.size() + truth->landmarks.size();
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    std::istringstream words(text);
    std::vector<std::string> t;
    for (std::string w; words >> w;) t.push_back(w);
    if (t.empty() || t[0][0] == '#') continue;
    const std::string& tag = t[0];
    const bool numeric = std::isdigit(static_cast<unsigned char>(tag[0])) != 0;
    if (tag == "EDGE_SE2" || tag == "EDGE_SE2_XY" || tag == "EDGE2" || tag == "ODOMETRY" || tag == "LANDMARK" ||
        tag == "FIX")
      continue;  // a graph file's measurements: only its vertices are truth
    const size_t first = numeric ? 0 : 1;  // index of the id
    const size_t values = t.size() - first - 1;
    const bool pose = numeric ? values == 3 : (tag == "VERTEX_SE2" || tag == "VERTEX2");
    if (!numeric && !pose && tag != "VERTEX_XY")
      throw InputError(path, line, "unknown tag '" + tag + "' in a ground-truth file", kTruthForm);
    if (values != (pose ? 3u : 2u) || (numeric && values != 2 && values != 3))
      throw InputError(path, line, "a ground-truth line has " + std::to_string(t.size()) + " fields", kTruthForm);
    const int id = ParseId(t[first], path, line);
    const double x = ParseNumber(t[first + 1], path, line), y = ParseNumber(t[first + 2], path, line);
    if (pose)
      Insert(truth->poses, truth->pose_line, id, SE2(x, y, ParseNumber(t[first + 3], path, line)), "pose", path, line);
    else
      Insert(truth->landmarks, truth->landmark_line, id, Eigen::Vector2d(x, y), "landmark", path, line);
  }
  if (truth->poses.size() + truth->landmarks.size() == before)
    throw InputError(path, 0, "the ground-truth file has no poses or landmarks", kTruthForm);
}

Metrics ScoreAgainstTruth(const PoseGraphFile& file, const PoseGraph& solved, const VertexTruth& truth,
                          const std::string& truth_name) {
  Metrics m;
  std::vector<SE2> gt, est;
  for (size_t i = 0; i < solved.poses.size(); ++i)
    if (const auto it = truth.poses.find(file.vertex_ids[i]); it != truth.poses.end()) {
      gt.push_back(it->second);
      est.push_back(solved.poses[i]);
    }
  if (gt.empty() && !truth.poses.empty())
    throw InputError(truth_name, 0, "no true pose id matches a pose id of the graph",
                     "give the ground truth of this graph (ids as in the graph file)");
  m.matched_poses = static_cast<std::int64_t>(gt.size());
  // The evaluator's definitions (eval/evaluate.cpp): ATE as is, aligned ATE after Umeyama,
  // landmarks moved by the same alignment (identity when it is not valid).
  const AlignmentResult umeyama = UmeyamaAlignment(est, gt);
  if (!gt.empty()) m.ate = ComputeStatistics(AbsoluteTrajectoryErrors(gt, est).translation_m);
  if (umeyama.valid)
    m.ate_aligned = ComputeStatistics(AbsoluteTrajectoryErrors(gt, TransformPoses(umeyama.T_gt_est, est)).translation_m);
  m.alignment_valid = umeyama.valid;
  if (!umeyama.valid) m.alignment_reason = umeyama.reason;

  std::vector<LandmarkEstimate> estimated;
  std::vector<TrueLandmark> true_landmarks;
  for (size_t j = 0; j < solved.landmarks.size(); ++j)
    if (const auto it = truth.landmarks.find(file.landmark_ids[j]); it != truth.landmarks.end()) {
      estimated.push_back({.id = file.landmark_ids[j], .position = solved.landmarks[j]});
      true_landmarks.push_back({.id = it->first, .position = it->second});
    }
  if (!estimated.empty()) {
    const SE2 T = umeyama.valid ? umeyama.T_gt_est : SE2();
    const LandmarkMapResult r =
        EvaluateLandmarkMap(estimated, true_landmarks, T, {.matching = LandmarkMatching::kById});
    m.landmark_rmse_m = r.rmse_m;
    m.landmark_matched = static_cast<std::int64_t>(r.matches.size());
  }
  return m;
}

}  // namespace slambox
