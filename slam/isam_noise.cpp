#include "slam/isam_noise.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "core/error.hpp"

namespace slambox {

const EnumNames<IsamNoise>& IsamNoiseNames() {
  static const EnumNames<IsamNoise> names = {
      {IsamNoise::kAuto, "auto"}, {IsamNoise::kSqrtInformation, "sqrt-information"}, {IsamNoise::kCovariance, "covariance"}};
  return names;
}

namespace {

std::vector<std::string_view> Words(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (j > i) words.push_back(line.substr(i, j - i));
    i = j;
  }
  return words;
}

// Where the diagonal values sit on a line of this tag (none: not an iSAM-family line).
std::vector<size_t> DiagonalPositions(std::string_view tag, size_t words, bool isam_edge2) {
  if ((tag == "ODOMETRY" || (tag == "EDGE2" && isam_edge2)) && words == 12) return {6, 9, 11};
  if (tag == "LANDMARK" && words == 8) return {5, 7};
  return {};
}

}  // namespace

std::optional<IsamNoise> ResolveIsamNoise(const std::string& text, const std::string& name, IsamNoise requested,
                                          bool isam_edge2) {
  int line = 0, above_line = 0, below_line = 0;
  double above = 0.0, below = 0.0;
  bool any = false;
  for (size_t pos = 0; pos < text.size();) {
    ++line;
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::vector<std::string_view> w = Words(std::string_view(text).substr(pos, end - pos));
    pos = end + 1;
    if (w.empty()) continue;
    for (size_t k : DiagonalPositions(w[0], w.size(), isam_edge2)) {
      const std::string s(w[k]);
      char* stop = nullptr;
      const double v = std::strtod(s.c_str(), &stop);
      if (stop == s.c_str() || *stop != '\0') continue;
      any = true;
      // |v| > 1: a square root's entry (its sign is free); 0 < v < 1: a variance. Zero fits
      // neither (the reader refuses it).
      if (std::abs(v) > 1.0 && above_line == 0) above_line = line, above = v;
      if (v > 0.0 && v < 1.0 && below_line == 0) below_line = line, below = v;
    }
  }
  if (!any) return std::nullopt;
  if (requested != IsamNoise::kAuto) return requested;
  if (above_line > 0 && below_line > 0)
    throw InputError(name, std::max(above_line, below_line),
                     "the noise values read as iSAM's square-root information on line " + std::to_string(above_line) +
                         " (diagonal " + std::to_string(above) + " > 1) but as a covariance on line " +
                         std::to_string(below_line) + " (diagonal " + std::to_string(below) + " < 1)",
                     "say which the file holds: --noise sqrt-information (iSAM) or --noise covariance (GTSAM)");
  return below_line > 0 ? IsamNoise::kCovariance : IsamNoise::kSqrtInformation;
}

namespace {
template <int N>
std::optional<Eigen::Matrix<double, N, N>> FromUpper(const Eigen::Matrix<double, N, N>& upper, IsamNoise noise) {
  using Matrix = Eigen::Matrix<double, N, N>;
  if (noise == IsamNoise::kCovariance) {
    const Matrix C = upper.template selfadjointView<Eigen::Upper>();
    const Eigen::LLT<Matrix> llt(C);
    if (llt.info() != Eigen::Success) return std::nullopt;
    const Matrix information = llt.solve(Matrix::Identity());
    return Matrix(0.5 * (information + information.transpose()));
  }
  for (int i = 0; i < N; ++i)
    if (upper(i, i) == 0.0) return std::nullopt;
  const Matrix R = upper.template triangularView<Eigen::Upper>();
  return Matrix(R.transpose() * R);
}
}  // namespace

std::optional<Eigen::Matrix3d> IsamPoseInformation(const double (&v)[6], IsamNoise noise) {
  Eigen::Matrix3d upper = Eigen::Matrix3d::Zero();
  upper(0, 0) = v[0], upper(0, 1) = v[1], upper(0, 2) = v[2], upper(1, 1) = v[3], upper(1, 2) = v[4], upper(2, 2) = v[5];
  return FromUpper<3>(upper, noise);
}

std::optional<Eigen::Matrix2d> IsamPointInformation(const double (&v)[3], IsamNoise noise) {
  Eigen::Matrix2d upper = Eigen::Matrix2d::Zero();
  upper(0, 0) = v[0], upper(0, 1) = v[1], upper(1, 1) = v[2];
  return FromUpper<2>(upper, noise);
}

}  // namespace slambox
