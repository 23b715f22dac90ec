// Geometric validation of a parsed scenario. The robot is a disc of radius r: a pose is
// valid when the disc touches no wall, box, circle or post; a straight drive from a to b
// is valid when the swept capsule {p : dist(p, [a,b]) < r} does (turn-then-drive).
// Boxes, circles and posts are solid; polylines and polygons are thin walls, so a robot
// may start inside a room drawn as a polygon.
#include <algorithm>
#include <Eigen/Geometry>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "sim/grid_contours.hpp"
#include "sim/scenario_yaml.hpp"

namespace slambox::scenario_detail {
namespace {

using Vec = Eigen::Vector2d;

double Cross(const Vec& a, const Vec& b) { return a.x() * b.y() - a.y() * b.x(); }

double PointSegmentDistance(const Vec& p, const Vec& a, const Vec& b) {
  const Vec ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

bool SegmentsIntersect(const Vec& p1, const Vec& p2, const Vec& q1, const Vec& q2) {
  const double d1 = Cross(p2 - p1, q1 - p1), d2 = Cross(p2 - p1, q2 - p1);
  const double d3 = Cross(q2 - q1, p1 - q1), d4 = Cross(q2 - q1, p2 - q1);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

double SegmentSegmentDistance(const Vec& p1, const Vec& p2, const Vec& q1, const Vec& q2) {
  if (SegmentsIntersect(p1, p2, q1, q2)) return 0.0;
  return std::min({PointSegmentDistance(p1, q1, q2), PointSegmentDistance(p2, q1, q2),
                   PointSegmentDistance(q1, p1, p2), PointSegmentDistance(q2, p1, p2)});
}

/// A solid or thin obstacle: its boundary segments, or a disc; `what` names it for users.
struct Obstacle {
  std::vector<std::pair<Vec, Vec>> edges;
  bool solid_box = false;  ///< edges enclose a solid box (a point inside also collides)
  Vec center = Vec::Zero();
  double radius_m = -1.0;  ///< >= 0 for discs
  std::string what;
  int line = 0;
};

std::vector<std::pair<Vec, Vec>> BoxEdges(const WallSpec& w) {
  const double a = w.angle_deg * M_PI / 180.0;
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(a).toRotationMatrix();
  const Vec h = 0.5 * w.size;
  const Vec c[4] = {w.center + R * Vec(-h.x(), -h.y()), w.center + R * Vec(h.x(), -h.y()),
                    w.center + R * Vec(h.x(), h.y()), w.center + R * Vec(-h.x(), h.y())};
  return {{c[0], c[1]}, {c[1], c[2]}, {c[2], c[3]}, {c[3], c[0]}};
}

std::vector<Obstacle> StaticObstacles(const Scenario& s) {
  std::vector<Obstacle> out;
  for (const WallSpec& w : s.walls) {
    Obstacle o;
    o.line = w.line;
    switch (w.kind) {
      case WallSpec::Kind::kPolyline:
      case WallSpec::Kind::kPolygon:
        o.what = w.kind == WallSpec::Kind::kPolyline ? "polyline wall" : "polygon wall";
        for (std::size_t i = 0; i + 1 < w.points.size(); ++i) o.edges.emplace_back(w.points[i], w.points[i + 1]);
        if (w.kind == WallSpec::Kind::kPolygon) o.edges.emplace_back(w.points.back(), w.points.front());
        break;
      case WallSpec::Kind::kBox:
        o.what = "box";
        o.edges = BoxEdges(w);
        o.solid_box = true;
        o.center = w.center;
        break;
      case WallSpec::Kind::kCircle:
        o.what = "circle";
        o.center = w.center;
        o.radius_m = w.radius_m;
        break;
    }
    out.push_back(o);
  }
  if (s.occupancy_grid.width > 0) {  // the map image's walls, as MakeWorld builds them
    Obstacle o;
    o.what = "occupied cells of world.occupancy_map";
    o.line = s.occupancy_map_line;
    for (const Contour& loop : OccupiedContours(s.occupancy_grid))
      for (std::size_t i = 0; i < loop.size(); ++i) o.edges.emplace_back(loop[i], loop[(i + 1) % loop.size()]);
    out.push_back(o);
  }
  for (const LandmarkSpec& l : s.landmarks) {
    Obstacle o;
    o.what = "landmark post " + std::to_string(l.id);
    o.center = l.pos;
    o.radius_m = l.radius_m;
    o.line = l.line;
    out.push_back(o);
  }
  return out;
}

bool InsideBox(const Obstacle& o, const Vec& p) {
  // Convex quadrilateral with counter-clockwise or clockwise edges: same side of all.
  int pos = 0, neg = 0;
  for (const auto& [a, b] : o.edges) (Cross(b - a, p - a) > 0 ? pos : neg)++;
  return pos == 4 || neg == 4;
}

/// Smallest gap between a disc of radius r swept along [a, b] and the obstacle (< 0: overlap).
double Clearance(const Obstacle& o, const Vec& a, const Vec& b, double r) {
  if (o.radius_m >= 0.0) return PointSegmentDistance(o.center, a, b) - o.radius_m - r;
  if (o.solid_box && InsideBox(o, a)) return -r;
  double d = 1e300;
  for (const auto& [p, q] : o.edges) d = std::min(d, SegmentSegmentDistance(a, b, p, q));
  return d - r;
}

std::string Num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string Point(const Vec& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

std::string Where(const Obstacle& o) {
  return "the " + o.what + (o.line > 0 ? " at line " + std::to_string(o.line) : std::string());
}

// Inside the map image's occupied region (its edges alone miss a point deep inside a wall).
bool InOccupiedCell(const OccupancyGrid& g, const Vec& p) {
  if (g.width <= 0) return false;
  const int ix = static_cast<int>(std::floor((p.x() - g.origin_m.x()) / g.resolution_m));
  const int iy = static_cast<int>(std::floor((p.y() - g.origin_m.y()) / g.resolution_m));
  return ix >= 0 && iy >= 0 && ix < g.width && iy < g.height && g.cells[std::size_t(iy) * g.width + ix] > 50;
}

void CheckPose(const Scenario& s, const std::vector<Obstacle>& obstacles, const PoseSpec& pose, int line,
               const std::string& name, const std::string& key) {
  const Vec p(pose.x, pose.y);
  if (InOccupiedCell(s.occupancy_grid, p))
    throw InputError(s.source, line, name + " " + Point(p) + " is in an occupied cell of world.occupancy_map",
                     "move " + key + " into the map's free space");
  for (const Obstacle& o : obstacles)
    if (Clearance(o, p, p, s.robot.radius_m) < 0.0)
      throw InputError(s.source, line,
                       name + " " + Point(p) + " is inside or too close to " + Where(o) + " (robot radius " +
                           Num(s.robot.radius_m) + " m)",
                       "move " + key + " so the robot's disc clears every wall and post");
}

}  // namespace

void CheckScenarioGeometry(const Scenario& s) {
  const std::vector<Obstacle> obstacles = StaticObstacles(s);
  CheckPose(s, obstacles, s.robot.start, s.robot.start_line, "robot start", "robot.start");
  if (s.robot.kidnap) CheckPose(s, obstacles, s.robot.kidnap->to, s.robot.kidnap->line, "kidnap target", "robot.kidnap.to");

  // Legs driven: start -> w0 -> w1 ... -> wn, then wn -> w0 for each further lap.
  const auto& path = s.robot.path;
  auto check_leg = [&](const Vec& a, std::size_t to) {
    const int line = to < s.robot.path_lines.size() ? s.robot.path_lines[to] : 0;
    if (InOccupiedCell(s.occupancy_grid, path[to]))
      throw InputError(s.source, line,
                       "waypoint " + std::to_string(to) + " " + Point(path[to]) + " is in an occupied cell of world.occupancy_map",
                       "move the waypoint into the map's free space");
    for (const Obstacle& o : obstacles)
      if (Clearance(o, a, path[to], s.robot.radius_m) < 0.0)
        throw InputError(s.source, line,
                         "waypoint " + std::to_string(to) + " " + Point(path[to]) + " unreachable: the straight drive from " +
                             Point(a) + " comes within robot.radius_m (" + Num(s.robot.radius_m) +
                             " m) of " + Where(o),
                         "move the waypoint or add one in between so each straight leg clears walls and posts");
  };
  Vec from(s.robot.start.x, s.robot.start.y);
  for (std::size_t i = 0; i < path.size(); ++i) {
    check_leg(from, i);
    from = path[i];
  }
  if (s.robot.laps > 1 && path.size() > 1) check_leg(path.back(), 0);

  // Movers slide along their paths through static geometry only.
  for (std::size_t m = 0; m < s.movers.size(); ++m) {
    const MoverSpec& mover = s.movers[m];
    const double r = mover.is_box ? 0.5 * mover.size.norm() : mover.radius_m;
    for (std::size_t i = 0; i + 1 < mover.path.size(); ++i)
      for (const Obstacle& o : obstacles)
        if (Clearance(o, mover.path[i], mover.path[i + 1], r) < 0.0)
          throw InputError(s.source, mover.line,
                           "mover " + std::to_string(m) + "'s path from " + Point(mover.path[i]) + " to " +
                               Point(mover.path[i + 1]) + " runs into " + Where(o),
                           "move the path so the mover (bounding radius " + Num(r) +
                               " m) clears every wall and post");
  }
}

}  // namespace slambox::scenario_detail
