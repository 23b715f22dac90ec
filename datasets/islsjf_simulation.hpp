#pragma once
// The simulated range-bearing runs of the 2D-I-SLSJF release (Huang, Wang & Dissanayake,
// OpenSLAM `2d-i-slsjf`; ../shared/data/landmark/sim_535/) -> Stream, so the landmark
// modules replay a run made by another simulator, with its ground truth. A directory holds
//   store_speed.txt, store_turnrate.txt  measured speed v [m/s] and turn rate w [rad/s], one per step
//   sensor_data.txt   rows `i id range bearing 0 0 0`: beacon `id` seen from the robot pose
//                     that precedes step i (1-based; pose i - 1 of the chain 0, 1, ...)
//   parameters.txt    `TimeInterval = dt`, `sigv`, `sigomega`, `sigr`, `sigtheta` (values such as
//                     `0.02;` or `(4*pi/180);`). The file calls them variances; they are standard
//                     deviations: sim_535's residuals against its own ground truth are
//                     0.094 m / 1.00 deg for sigr = 0.1 m / sigtheta = 1 deg, and the pose index
//                     i - 1 is the one that gives those residuals (i gives 2.8 deg).
//   store_robotTrue.txt (x y phi per pose), store_beaconsTrue.txt (id x y): ground truth, optional.
// Motion model (parameters.txt): x' = x + v dt cos(phi + w dt), y' = y + v dt sin(phi + w dt),
// phi' = phi + w dt, so step k in pose k's frame is (v dt cos(w dt), v dt sin(w dt), w dt) with
// covariance J diag(sigv^2, sigomega^2) J^T, J = d(step)/d(v, w); the header's odometry noise is
// Thrun's model fitted to those covariances (datasets/landmark_log.hpp).
#include <array>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "core/stream.hpp"

namespace slambox {

struct IslsjfSimulationOptions {
  // Empty: read from the directory's parameters.txt.
  std::optional<double> time_interval_s;       ///< [s] between steps
  std::optional<double> sigma_speed_mps;       ///< [m/s] speed noise (standard deviation)
  std::optional<double> sigma_turnrate_deg_s;  ///< [deg/s] turn-rate noise
  std::optional<double> sigma_range_m;         ///< [m] range noise
  std::optional<double> sigma_bearing_deg;     ///< [deg] bearing noise
  /// [m] the detector's range; empty: the farthest observation (noise makes it overshoot the
  /// true limit by about two sigma_range; sim_535: 3.17 m for a 3 m sensor).
  std::optional<double> range_max_m;
  /// [deg] field of view, centred ahead; empty: twice the widest bearing observed, at most 360.
  std::optional<double> fov_deg;
  std::optional<std::array<double, 4>> odometry_alpha;  ///< Thrun's model; empty: fitted
};

struct IslsjfSimulationReport {
  int steps = 0, observations = 0, beacons_seen = 0;
  double time_interval_s = 0.0, range_max_m = 0.0, fov_deg = 0.0;
  bool ground_truth = false;
};

/// One step of the file's motion model in the pose's own frame, (v dt cos(w dt), v dt sin(w dt), w dt),
/// and its covariance J diag(sigma_v^2, sigma_w^2) J^T with J = d(step)/d(v, w).
struct UnicycleStep {
  SE2 increment;
  Eigen::Matrix3d covariance;
};
UnicycleStep IslsjfStep(double v_mps, double w_radps, double dt_s, double sigma_v_mps, double sigma_w_radps);

/// Throws InputError naming the file and line: a missing file or parameter, a row of the wrong
/// width, a pose or beacon index out of range, speed and turn-rate files of different lengths.
Stream ReadIslsjfSimulation(const std::string& dir, const IslsjfSimulationOptions& options = {},
                            IslsjfSimulationReport* report = nullptr);

}  // namespace slambox
