#pragma once
// Dynamic Covariance Scaling as a Ceres robust loss.
#include <ceres/loss_function.h>

namespace slambox {

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
