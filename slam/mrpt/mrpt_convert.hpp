#pragma once
// The edge between slambox's stream types and MRPT 2.5's: every MRPT type a module sees
// is made here, and every result comes back through here. Nothing outside slam/mrpt/
// includes this header (MRPT must not leak into core/ or slam/).
#include <array>
#include <cstdint>

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/slam/CICP.h>

#include "core/estimate.hpp"
#include "core/odometry_model.hpp"
#include "core/sensors.hpp"
#include "core/stream.hpp"
#include "slam/mrpt/mrpt_icp_params.hpp"

namespace slambox::mrpt_bridge {

inline mrpt::poses::CPose2D ToMrpt(const SE2& T) { return {T.x, T.y, T.theta}; }
inline SE2 FromMrpt(const mrpt::poses::CPose2D& T) { return {T.x(), T.y(), T.phi()}; }
/// Stream times are seconds since the run's start; MRPT stamps are absolute clock times.
inline mrpt::Clock::time_point ToMrptTime(double t_s) { return mrpt::Clock::fromDouble(t_s); }

/// The module's `icp_*` keys into MRPT's CICP settings (angles in radians there); the
/// fields CICP has beyond them keep their values.
void SetIcpParams(const MrptIcpParams& p, mrpt::slam::CICP::TConfigParams& out);

/// Seeds MRPT's global random generator (particle filters, motion-model sampling).
void SeedMrptRandom(std::uint64_t seed);

/// Odometry accumulated between two MRPT updates: the increment T_prev_now (composition of
/// the stream's deltas) and its covariance, propagated from zero exactly as dead
/// reckoning does (P' = G P Gᵀ + V M Vᵀ, Thrun Table 5.6, starting at the identity).
struct OdometryAccumulator {
  SE2 increment;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double t_s = 0.0;  ///< time of the latest delta
  bool empty = true;
  void Add(const OdometryEvent& odometry, const std::array<double, 4>& alpha);
  void Reset() { *this = OdometryAccumulator{}; }
};

/// Floor on the action's standard deviations: a zero-motion increment has a zero
/// covariance, which MRPT's EKF and particle sampling cannot factor.
struct ActionNoiseFloor {
  double sigma_xy_m = 1e-4;
  double sigma_theta_rad = 1e-4;
};

/// OdometryEvent(s) → CActionRobotMovement2D with MRPT's Gaussian model (mmGaussian) whose
/// covariance is the Thrun-model covariance of the increment (linearized, plus the floor).
mrpt::obs::CActionRobotMovement2D ToMrptAction(const OdometryAccumulator& odometry, const ActionNoiseFloor& floor);

/// Makes MRPT re-derive the action's noise with its Thrun model (what CMetricMapBuilderRBPF
/// does: it rebuilds the action from the accumulated mean and motionModelConfiguration).
/// MRPT's model draws std = α1|rot1| + α2|trans| (rot1, rot2) and α3|trans| + α4(|rot1| +
/// |rot2|) (trans), linear in the motion, where ours has variance a1 rot1² + a2 trans²;
/// αi = scale·√ai gives a std between 1 and √2 times ours for one increment.
void UseMrptThrunModel(mrpt::obs::CActionRobotMovement2D& action, const std::array<double, 4>& alpha, double scale);

/// Makes MRPT re-derive the action's noise with its Gaussian model (mmGaussian), whose
/// stds are linear in the motion: σ_xy = minStdXY + a1·|Δ| + a2·|Δφ| on x and y, σ_φ =
/// minStdPHI + a3·|Δ| + a4·|Δφ| (all radians). From our variance model (trans² ~ a3 Δ²
/// + a4 rot², rot² ~ a1 rot² + a2 Δ²): a1 = scale·√a3, a2 = scale·√a4, a3 = scale·√a2,
/// a4 = scale·√a1; the minima are the floor's stds. Unlike MRPT's Thrun model (a
/// CPosePDFParticles whose unnormalized weights make every draw return its first sample,
/// so all RBPF particles get the same increment), this PDF is sampled properly.
void UseMrptGaussianModel(mrpt::obs::CActionRobotMovement2D& action, const std::array<double, 4>& alpha, double scale,
                          const ActionNoiseFloor& floor);

/// LaserScanEvent → CObservation2DRangeScan for an occupancy grid that both inserts the
/// scan and scores it. MRPT 2.5 is inconsistent here: points (likelihood field, ICP) put
/// beam i at -aperture/2 + i·aperture/(N-1), grid insertion at -aperture/2 +
/// i·aperture/N, so the map is rotated against the scored scan by i·aperture/(N(N-1))
/// (half a beam step on average, 0.5° for 360 beams) and every insert-then-match cycle
/// turns the estimate further (measured: 4° heading drift in 23 s on `loop`). Here each
/// beam is followed by upsampling-1 invalid beams (N' = upsampling·N, step/upsampling):
/// the valid beams are exactly at their angles for points, and grid insertion with
/// decimation = upsampling visits only them, off by at most one fine step (i·step/N').
mrpt::obs::CObservation2DRangeScan ToMrptScanForGrid(const LaserScanEvent& scan, double sigma_range_m, int upsampling);

/// LaserScanEvent → CObservation2DRangeScan. MRPT spaces beams by aperture / (N - 1),
/// right to left from -aperture/2 in the sensor frame, so aperture = (N - 1) * increment
/// and the sensor is yawed by the scan's centre direction angle_min + aperture / 2: beam
/// i is then exactly at angle_min + i * increment. Invalid beams stay invalid (range_max).
mrpt::obs::CObservation2DRangeScan ToMrptScan(const LaserScanEvent& scan, double sigma_range_m);
/// The inverse of ToMrptScan (angles through MRPT's float aperture: ~1e-7 rad).
LaserScanEvent FromMrptScan(const mrpt::obs::CObservation2DRangeScan& scan, double t_s);

/// LandmarkEvent → CObservationBearingRange: yaw = bearing (counter-clockwise, robot
/// frame, sensor at the robot origin), pitch 0, landmarkID = the stream's id (or
/// INVALID_LANDMARK_ID = -1 when unknown), stds from the sensor configuration.
mrpt::obs::CObservationBearingRange ToMrptBearingRange(const LandmarkEvent& event, const LandmarkSensorConfig& cfg);

/// An MRPT pose expressed in the frame where MRPT started at the identity, mapped back to
/// the world by the stream's start pose: T_w = T_w_start * T_start.
inline SE2 ToWorld(const SE2& T_w_start, const SE2& T_start) { return T_w_start * T_start; }
/// Rotates a covariance over (x, y, theta) from the start frame into the world frame.
Eigen::Matrix3d CovarianceToWorld(const SE2& T_w_start, const Eigen::Matrix3d& cov_start);

}  // namespace slambox::mrpt_bridge
