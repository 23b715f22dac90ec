#pragma once
// The yaw angle manifold for Ceres (after Ceres' examples/slam/pose_graph_2d), and the
// pose manifold of one (x, y, yaw) parameter block.
#include <ceres/autodiff_manifold.h>
#include <ceres/jet.h>
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>

#include "core/se2.hpp"

namespace slambox {

/// The value part of a scalar or a Ceres Jet (the wrap offset is piecewise constant).
inline double ScalarPart(double v) { return v; }
template <typename T, int N>
double ScalarPart(const ceres::Jet<T, N>& v) {
  return v.a;
}

/// Yaw lives on the circle: x [+] delta = NormalizeAngle(x + delta) (Ceres' AngleManifold).
/// The wrap subtracts a multiple of 2 pi found from the value part, so the derivative is 1.
struct AngleManifoldFunctor {
  template <typename T>
  bool Plus(const T* x, const T* delta, T* x_plus_delta) const {
    const T sum = x[0] + delta[0];
    *x_plus_delta = sum + (NormalizeAngle(ScalarPart(sum)) - ScalarPart(sum));
    return true;
  }
  template <typename T>
  bool Minus(const T* y, const T* x, T* y_minus_x) const {
    const T diff = y[0] - x[0];
    *y_minus_x = diff + (NormalizeAngle(ScalarPart(diff)) - ScalarPart(diff));
    return true;
  }
};

inline ceres::Manifold* MakeAngleManifold() {
  return new ceres::AutoDiffManifold<AngleManifoldFunctor, 1, 1>;
}

/// A pose block (x, y, theta): Euclidean in x, y and the angle manifold in theta.
using PoseManifold =
    ceres::ProductManifold<ceres::EuclideanManifold<2>, ceres::AutoDiffManifold<AngleManifoldFunctor, 1, 1>>;

}  // namespace slambox
