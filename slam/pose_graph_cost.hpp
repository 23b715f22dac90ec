#pragma once
// Ceres pieces of the 2D pose graph (after Ceres' examples/slam/pose_graph_2d): the edge
// cost with analytic Jacobians, the yaw angle manifold, and the DCS robust loss.
#include <ceres/autodiff_manifold.h>
#include <ceres/jet.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

#include "core/se2.hpp"

namespace slambox {

/// Whitened edge residual r = U e with U^T U = Omega (U upper-triangular Cholesky factor),
/// so |r|^2 = e^T Omega e. Parameter blocks: pose_i = (x [m], y [m], theta [rad]), pose_j.
class PoseGraphEdgeCost final : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  PoseGraphEdgeCost(const SE2& T_ij, const Eigen::Matrix3d& sqrt_information)
      : T_ij_(T_ij), sqrt_information_(sqrt_information) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  SE2 T_ij_;
  Eigen::Matrix3d sqrt_information_;
};

/// Upper-triangular U with U^T U = information; returns false unless information is
/// symmetric positive definite and finite.
bool SqrtInformation(const Eigen::Matrix3d& information, Eigen::Matrix3d* sqrt_information);

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

/// Dynamic Covariance Scaling (Agarwal, Tipaldi, Spinello, Stachniss, Burgard, ICRA 2013)
/// as an M-estimator on s = chi2 = |r|^2. DCS scales the residual by
///   k = min(1, 2 Phi / (Phi + s)),
/// i.e. an IRLS weight k^2 on s. The loss whose derivative is that weight is
///   rho(s) = s                          for s <= Phi,
///   rho(s) = 3 Phi - 4 Phi^2 / (Phi + s) for s > Phi  (continuous with slope 1 at s = Phi),
/// so rho'(s) = k^2 and Ceres' iteratively reweighted steps are DCS's.
class DcsLoss final : public ceres::LossFunction {
 public:
  explicit DcsLoss(double phi) : phi_(phi) {}
  void Evaluate(double s, double rho[3]) const override;

 private:
  double phi_;
};

}  // namespace slambox
