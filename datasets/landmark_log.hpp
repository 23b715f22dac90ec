#pragma once
// A chain of poses with odometry and point-landmark sightings, as landmark datasets state
// them (Victoria Park's preprocessed file, iSAM / GTSAM / g2o pose-landmark graphs) ->
// Stream, the same way for every format. The files have no times: pose k is put at
// t = k * pose_period_s. Sightings, given as a point (x, y) in the pose's frame with its
// covariance P, become (range, bearing) observations with the landmark's index as a known
// id. The header's landmark noise is the median over all sightings of their covariance in
// polar coordinates (J P J^T), and the odometry noise is Thrun's model fitted to the
// per-step covariances (datasets/odometry_noise_fit.hpp), so filters weight the data as the
// file does. Ground truth, where the dataset has it (cityTrees10000), is the true pose of
// every chain pose and the true landmarks.
#include <Eigen/Core>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/stream.hpp"

namespace slambox {

struct LandmarkLog {
  /// Step k (k = 1 .. n-1): pose k in pose k-1's frame, with its covariance over (x [m], y [m], theta [rad]).
  std::vector<SE2> increments;
  std::vector<Eigen::Matrix3d> increment_covariances;
  struct Sighting {
    int pose = 0;      ///< 0 .. n-1 (n = increments + 1)
    int landmark = 0;  ///< the dataset's landmark id (>= 0): the stream's known id
    Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< [m] in the pose's frame
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  ///< [m^2]
  };
  std::vector<Sighting> sightings;
  std::vector<SE2> true_poses;                         ///< empty, or one per chain pose
  std::map<int, Eigen::Vector2d> true_landmarks;       ///< [m] by landmark id (may be empty)
};

struct LandmarkLogOptions {
  double pose_period_s = 0.2;  ///< [s] time between consecutive poses
  double fov_deg = 360.0;      ///< the detector's field of view, centred ahead (header only)
  /// The detector's range [m]; empty: the farthest sighting rounded up to a whole metre.
  std::optional<double> range_max_m = std::nullopt;
  /// Thrun's odometry noise; empty: fitted to the per-step covariances.
  std::optional<std::array<double, 4>> odometry_alpha = std::nullopt;
  std::string description = {};  ///< what the data is (the header's scenario comment)
};

/// Throws InputError naming `name` for bad options, a sighting at zero range or of a pose
/// outside the chain, or ground truth of the wrong length.
Stream AssembleLandmarkLog(const LandmarkLog& log, const std::string& name, const LandmarkLogOptions& options);

}  // namespace slambox
