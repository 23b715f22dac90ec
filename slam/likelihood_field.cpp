#include "slam/likelihood_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "slam/icp_target.hpp"

namespace slambox {

void SquaredDistanceTransform1d(std::vector<double>& f) {
  // Lower envelope of the parabolas y = (q - p)^2 + f[p] (Felzenszwalb & Huttenlocher).
  const int n = static_cast<int>(f.size());
  if (n == 0) return;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<int> v(n);         // parabola vertices in the envelope
  std::vector<double> z(n + 1);  // boundaries between them
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == inf) continue;
    while (k >= 0) {
      const double s = ((f[q] + q * q) - (f[v[k]] + v[k] * v[k])) / (2.0 * (q - v[k]));
      if (s > z[k]) {
        z[k + 1] = s;
        break;
      }
      --k;
    }
    if (k < 0) z[0] = -inf;
    v[++k] = q;
    z[k + 1] = inf;
  }
  if (k < 0) return;  // nothing finite: all stay +inf
  std::vector<double> d(n);
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[j + 1] < q) ++j;
    d[q] = (q - v[j]) * static_cast<double>(q - v[j]) + f[v[j]];
  }
  f = std::move(d);
}

DistanceGrid MakeDistanceGrid(const std::vector<Eigen::Vector2d>& occupied, double resolution_m,
                              double max_distance_m, double margin_m) {
  DistanceGrid g;
  g.resolution_m = resolution_m;
  g.max_distance_m = max_distance_m;
  if (occupied.empty()) return g;
  Eigen::Vector2d lo = occupied.front(), hi = occupied.front();
  for (const auto& p : occupied) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  g.origin = lo.array() - margin_m;
  const double width = std::ceil((hi.x() - lo.x() + 2 * margin_m) / resolution_m) + 1;
  const double height = std::ceil((hi.y() - lo.y() + 2 * margin_m) / resolution_m) + 1;
  if (!(width * height <= static_cast<double>(limits::kMaxGridCells)))
    throw InputError("the map", 0,
                     "a distance grid of " + std::to_string(width) + " x " + std::to_string(height) + " cells at " +
                         std::to_string(resolution_m) + " m exceeds the limit of " +
                         std::to_string(limits::kMaxGridCells) + " cells (core/limits.hpp)",
                     "use a coarser grid (--set algo.NAME.grid_resolution_m) or a smaller world");
  g.width = static_cast<int>(width);
  g.height = static_cast<int>(height);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> d2(static_cast<size_t>(g.width) * g.height, inf);
  for (const auto& p : occupied) {
    const int ix = static_cast<int>(std::floor((p.x() - g.origin.x()) / resolution_m));
    const int iy = static_cast<int>(std::floor((p.y() - g.origin.y()) / resolution_m));
    d2[static_cast<size_t>(iy) * g.width + ix] = 0.0;
  }
  // Separable: columns, then rows (squared distances in cells).
  std::vector<double> line;
  for (int x = 0; x < g.width; ++x) {
    line.resize(g.height);
    for (int y = 0; y < g.height; ++y) line[y] = d2[static_cast<size_t>(y) * g.width + x];
    SquaredDistanceTransform1d(line);
    for (int y = 0; y < g.height; ++y) d2[static_cast<size_t>(y) * g.width + x] = line[y];
  }
  g.distance_m.assign(d2.size(), static_cast<float>(max_distance_m));
  const IcpTarget cloud = MakeCloudTarget(occupied, {.normal_neighbors = 3, .build_kd_tree = true});
  // Cells whose grid distance is within the clamp plus the half-diagonal of two cells.
  const double band_cells = max_distance_m / resolution_m + 1.5;
  for (int y = 0; y < g.height; ++y) {
    line.assign(d2.begin() + static_cast<long>(y) * g.width, d2.begin() + static_cast<long>(y + 1) * g.width);
    SquaredDistanceTransform1d(line);
    for (int x = 0; x < g.width; ++x) {
      if (line[x] > band_cells * band_cells) continue;
      const Eigen::Vector2d centre = g.origin + resolution_m * Eigen::Vector2d(x + 0.5, y + 0.5);
      int index = 0;
      double dist2 = 0.0;
      NearestByKdTree(cloud, centre, &index, &dist2);
      g.distance_m[static_cast<size_t>(y) * g.width + x] = static_cast<float>(std::min(max_distance_m, std::sqrt(dist2)));
    }
  }
  return g;
}

}  // namespace slambox
