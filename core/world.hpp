#pragma once
// Ground-truth world geometry as plain data: what eval rasterizes and render draws.
// Boxes and polygons are already reduced to their boundary segments.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace slambox {

struct Segment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  ///< [m] world frame
  Eigen::Vector2d b = Eigen::Vector2d::Zero();  ///< [m] world frame
};

struct Circle {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< [m]
  double radius_m = 0.0;
};

/// A physical post seen by the landmark detector.
struct TrueLandmark {
  int id = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< [m]
  double radius_m = 0.1;
};

/// A dynamic obstacle's path, for drawing; its shape is a circle or a box.
struct MoverTrack {
  std::vector<Eigen::Vector2d> path;  ///< [m] waypoints
  double radius_m = 0.0;              ///< > 0 for circles
  Eigen::Vector2d box_size_m = Eigen::Vector2d::Zero();  ///< > 0 for boxes
};

struct World {
  std::vector<Segment> wall_segments;
  std::vector<Circle> wall_circles;
  std::vector<TrueLandmark> landmarks;
  std::vector<MoverTrack> movers;
};

/// Axis-aligned bounds of every wall, landmark and mover path (empty world: zeros).
struct Bounds {
  Eigen::Vector2d min = Eigen::Vector2d::Zero();
  Eigen::Vector2d max = Eigen::Vector2d::Zero();
};
Bounds WorldBounds(const World& world);

}  // namespace slambox
