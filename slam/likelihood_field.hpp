#pragma once
// The likelihood-field range model's distance grid (Thrun, Prob. Robotics, Table 6.3):
// at every cell centre, the distance to the nearest wall point, interpolated bilinearly
// between centres. Felzenszwalb & Huttenlocher's separable squared distance transform
// (Theory of Computing 2012, O(cells)) finds the cells within the clamp distance; only
// those get the exact distance from a kd-tree. (Cell-to-cell distances alone bias the
// field by up to a cell: a wall on a cell boundary looks a cell deeper from one side.)
#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace slambox {

struct DistanceGrid {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< [m] corner of cell (0, 0)
  double resolution_m = 0.05;
  int width = 0, height = 0;
  double max_distance_m = 1.0;     ///< distances are clamped here (and outside the grid)
  std::vector<float> distance_m;   ///< row-major, width * height

  /// Distance from p to the nearest wall point, bilinear between cell centres;
  /// max_distance_m outside the grid.
  double At(const Eigen::Vector2d& p) const {
    const double fx = (p.x() - origin.x()) / resolution_m - 0.5, fy = (p.y() - origin.y()) / resolution_m - 0.5;
    const int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
    if (ix < 0 || iy < 0 || ix + 1 >= width || iy + 1 >= height) return max_distance_m;
    const double u = fx - ix, v = fy - iy;
    const float* c = &distance_m[static_cast<size_t>(iy) * width + ix];
    return (1 - v) * ((1 - u) * c[0] + u * c[1]) + v * ((1 - u) * c[width] + u * c[width + 1]);
  }
};

/// Exact 1-D squared distance transform of f (0 at occupied cells, +inf elsewhere; any
/// non-negative costs), in place: d[q] = min_p (q - p)^2 + f[p].
void SquaredDistanceTransform1d(std::vector<double>& f);

/// Grid over [lo - margin, hi + margin] of the wall points `occupied` (spaced finer than
/// the resolution), each centre holding min(distance to the nearest point, max_distance_m).
DistanceGrid MakeDistanceGrid(const std::vector<Eigen::Vector2d>& occupied, double resolution_m,
                              double max_distance_m, double margin_m);

}  // namespace slambox
