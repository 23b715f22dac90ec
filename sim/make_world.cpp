// MakeWorld: scenario walls, posts and mover paths reduced to plain ground-truth geometry.
#include <cmath>

#include "core/se2.hpp"
#include "sim/grid_contours.hpp"
#include "sim/scenario.hpp"

namespace slambox {

namespace {
void AddChain(const std::vector<Eigen::Vector2d>& pts, bool closed, World& w) {
  for (size_t i = 0; i + 1 < pts.size(); ++i) w.wall_segments.push_back({pts[i], pts[i + 1]});
  if (closed && pts.size() > 2) w.wall_segments.push_back({pts.back(), pts.front()});
}

/// Corners of a box of full extents `size` rotated by `angle_deg` about `center`, in order.
std::vector<Eigen::Vector2d> BoxCorners(const Eigen::Vector2d& center, const Eigen::Vector2d& size, double angle_deg) {
  const Eigen::Matrix2d R = RotationMatrix(angle_deg * M_PI / 180.0);
  const Eigen::Vector2d h = size / 2.0;
  return {center + R * Eigen::Vector2d(-h.x(), -h.y()), center + R * Eigen::Vector2d(h.x(), -h.y()),
          center + R * Eigen::Vector2d(h.x(), h.y()), center + R * Eigen::Vector2d(-h.x(), h.y())};
}
}  // namespace

World MakeWorld(const Scenario& scenario) {
  World w;
  // A map image's walls: the boundary loops of its occupied cells, exact (the cells'
  // sides), so the LIDAR, Box2D, figures and map-based modules all see the grid.
  for (const Contour& loop : OccupiedContours(scenario.occupancy_grid)) AddChain(loop, true, w);
  for (const WallSpec& wall : scenario.walls) {
    switch (wall.kind) {
      case WallSpec::Kind::kPolyline: AddChain(wall.points, false, w); break;
      case WallSpec::Kind::kPolygon: AddChain(wall.points, true, w); break;
      case WallSpec::Kind::kBox: AddChain(BoxCorners(wall.center, wall.size, wall.angle_deg), true, w); break;
      case WallSpec::Kind::kCircle: w.wall_circles.push_back({wall.center, wall.radius_m}); break;
    }
  }
  for (const LandmarkSpec& lm : scenario.landmarks) w.landmarks.push_back({lm.id, lm.pos, lm.radius_m});
  for (const MoverSpec& m : scenario.movers) {
    MoverTrack t;
    t.path = m.path;
    if (m.is_box) t.box_size_m = m.size;
    else t.radius_m = m.radius_m;
    w.movers.push_back(t);
  }
  return w;
}

}  // namespace slambox
