#include "slam/dcs_loss.hpp"

namespace slambox {

void DcsLoss::Evaluate(double s, double rho[3]) const {
  if (s <= phi_) {
    rho[0] = s;
    rho[1] = 1.0;
    rho[2] = 0.0;
    return;
  }
  const double d = phi_ + s;
  rho[0] = 3.0 * phi_ - 4.0 * phi_ * phi_ / d;
  rho[1] = 4.0 * phi_ * phi_ / (d * d);
  rho[2] = -8.0 * phi_ * phi_ / (d * d * d);
}

}  // namespace slambox
