#pragma once
// What a SLAM module yields: the final (smoothed where the method smooths) trajectory,
// its map and per-step diagnostics. Plain data; eval scores it, render draws it.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct PoseEstimate {
  double t_s = 0.0;  ///< a stream event time
  SE2 pose;          ///< T_world_robot
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< over (x [m], y [m], theta [rad])
  bool has_covariance = false;
};

struct LandmarkEstimate {
  int id = -1;  ///< the module's id: the true id with known association, else its own index
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< [m] world frame
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  bool has_covariance = false;
};

/// A loop closure the module proposed, between the robot poses at two times.
struct LoopClosureRecord {
  double t_from_s = 0.0;
  double t_to_s = 0.0;
  SE2 T_from_to;  ///< measured relative pose of `to` in `from`'s frame
  bool accepted = false;
};

/// The pose graph as built (for figures): nodes at optimized poses, edges by kind.
struct PoseGraphView {
  struct Edge {
    int from = 0;
    int to = 0;
    bool loop_closure = false;
    bool accepted = true;  ///< false: rejected or switched off by the robust back-end
  };
  std::vector<double> node_t_s;
  std::vector<SE2> nodes;
  std::vector<Edge> edges;
};

/// Particle cloud at one step (FastSLAM), for figures.
struct ParticleSnapshot {
  double t_s = 0.0;
  std::vector<SE2> poses;
  std::vector<double> weights;  ///< normalized
};

/// What a module that associates its own detections did with one of them (scored by
/// `association_agreement`, eval/association_agreement.hpp). Modules that do not report
/// assignments leave Estimate::observation_assignments empty.
struct ObservationAssignment {
  int scan = 0;          ///< index of the LandmarkEvent among the stream's landmark events (0-based)
  int index = 0;         ///< the observation's index in that event
  /// The module's landmark id it updated or created (LandmarkEstimate::id; after merges the
  /// surviving landmark's), possibly of a landmark removed later; -1: not used (clutter,
  /// ambiguous, held).
  int landmark = -1;
  bool created = false;  ///< the observation created that landmark
};

/// Occupancy grid: cell (ix, iy) covers origin + [ix, ix+1) x [iy, iy+1) * resolution.
struct OccupancyGrid {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  double resolution_m = 0.05;
  int width = 0;
  int height = 0;
  std::vector<std::int8_t> cells;  ///< row-major (iy * width + ix); -1 unknown, 0 free .. 100 occupied
};

struct Estimate {
  std::vector<PoseEstimate> trajectory;  ///< time-ordered, at stream event times
  std::vector<LandmarkEstimate> landmarks;
  std::vector<Eigen::Vector2d> map_points;  ///< LIDAR points at the final poses [m]
  std::optional<OccupancyGrid> grid;
  std::vector<LoopClosureRecord> loop_closures;
  PoseGraphView pose_graph;
  std::vector<ParticleSnapshot> particles;
  /// Per detection, what the module assigned it to (one entry per observation of every
  /// landmark event, in stream order); empty when the module does not report it.
  std::vector<ObservationAssignment> observation_assignments;
  /// Named per-step series: name -> (t_s, value). E.g. "icp_iterations", "neff",
  /// "distinct_ancestors", "hessian_min_eigenvalue", "degenerate".
  std::map<std::string, std::vector<std::pair<double, double>>> diagnostics;
  /// Filled by Replay (not the module): wall time of each event's processing [s],
  /// and of Finish() [s].
  std::vector<double> step_time_s;
  double finish_time_s = 0.0;
};

}  // namespace slambox
