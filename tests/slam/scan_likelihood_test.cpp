// The Poisson scan likelihood (slam/scan_likelihood.hpp) against hand-computed values:
// robot at the origin, known exactly; one landmark at (10, 0) m with covariance 0.25 I m^2;
// range-bearing noise diag(0.01 m^2, 1e-4 rad^2). Its predicted observation is (10 m, 0),
// with S = diag(0.25 + 0.01, 0.25 / 10^2 + 1e-4) = diag(0.26, 0.0026) (the bearing's
// Jacobian is 1 / range); its probability of being in view (range 12 m, fov 180 deg) is
// Phi((12 - 10) / 0.5) [Phi(pi/2 / 0.05) - Phi(-pi/2 / 0.05)] = Phi(4) = 0.99996833.
// Expected values computed separately (Python, math.erfc).
#include "slam/scan_likelihood.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace slambox {
namespace {

struct Scene {
  EkfSlamState state;
  Eigen::Matrix2d R = Eigen::Vector2d(0.01, 1e-4).asDiagonal();
  ScanLikelihoodModel model{.false_density_per_m2 = 1e-3, .range_max_m = 12.0, .half_fov_rad = M_PI / 2};
  std::vector<double> p_detect = {0.9};
  explicit Scene(const Eigen::Vector2d& landmark = {10.0, 0.0}) {
    state.mean = (Eigen::VectorXd(5) << 0, 0, 0, landmark.x(), landmark.y()).finished();
    state.covariance = (Eigen::VectorXd(5) << 0, 0, 0, 0.25, 0.25).finished().asDiagonal();
  }
};

TEST(ScanLikelihood, ProbabilityInViewIsTheMassInsideRangeAndFieldOfView) {
  const Eigen::Matrix2d C = Eigen::Vector2d(4.0, 0.01).asDiagonal();
  // Range: Phi((12 - 10) / 2) = Phi(1); bearing 0 with sigma 0.1 rad deep inside +-90 deg.
  EXPECT_NEAR(ProbabilityInView({10.0, 0.0}, C, 12.0, M_PI / 2), 0.8413447460685429, 1e-12);
  // Predicted at the edge of the range or of the field of view: half the mass.
  EXPECT_NEAR(ProbabilityInView({12.0, 0.0}, C, 12.0, M_PI / 2), 0.5, 1e-12);
  EXPECT_NEAR(ProbabilityInView({1.0, M_PI / 2}, C, 12.0, M_PI / 2), 0.5, 1e-7);
  // 360 deg: the bearing does not matter.
  EXPECT_NEAR(ProbabilityInView({10.0, 3.0}, C, 12.0, M_PI), 0.8413447460685429, 1e-12);
  // Far beyond the range: nothing.
  EXPECT_LT(ProbabilityInView({20.0, 0.0}, Eigen::Vector2d(0.25, 0.01).asDiagonal(), 12.0, M_PI / 2), 1e-50);
}

TEST(ScanLikelihood, HandComputedDetectionOfOneLandmark) {
  const Scene s;
  // z = (10.5, 0.05): nu = (0.5, 0.05), d^2 = 0.25 / 0.26 + 0.0025 / 0.0026 = 1.9230769,
  // N = exp(-d^2 / 2) / (2 pi sqrt(0.26 * 0.0026)) = 2.3402160; log(1e-3 * 10.5 + 0.9 N)
  // less the expected detections 0.9 * 0.99996833.
  EXPECT_NEAR(ScanLogLikelihood(s.state, {{10.5, 0.05}}, s.R, s.p_detect, s.model), -0.1501158890603025, 1e-9);
}

TEST(ScanLikelihood, ALandmarkInViewThatIsNotSeenCostsItsExpectedDetections) {
  const Scene in_view;
  EXPECT_NEAR(ScanLogLikelihood(in_view.state, {}, in_view.R, in_view.p_detect, in_view.model), -0.8999714958823503,
              1e-12);
  // A detection far from it (d^2 > 50) is explained by the false-detection field alone:
  // log(1e-3 * 5) - 0.9 * 0.99996833.
  EXPECT_NEAR(ScanLogLikelihood(in_view.state, {{5.0, -1.0}}, in_view.R, in_view.p_detect, in_view.model),
              -6.1982888624303865, 1e-9);
  // The same landmark beyond the detector's reach is not expected: missing it costs nothing.
  const Scene out_of_view(Eigen::Vector2d(20.0, 0.0));
  EXPECT_NEAR(ScanLogLikelihood(out_of_view.state, {}, out_of_view.R, out_of_view.p_detect, out_of_view.model), 0.0,
              1e-12);
}

TEST(ScanLikelihood, DetectionsNearerTheirPredictionAreLikelier) {
  const Scene s;
  double previous = std::numeric_limits<double>::infinity();
  for (double offset_m : {0.0, 0.3, 0.6, 1.0, 2.0}) {
    const double log_p = ScanLogLikelihood(s.state, {{10.0 + offset_m, 0.0}}, s.R, s.p_detect, s.model);
    EXPECT_LT(log_p, previous) << offset_m;
    previous = log_p;
  }
}

}  // namespace
}  // namespace slambox
