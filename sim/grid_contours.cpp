#include "sim/grid_contours.hpp"

#include <cassert>
#include <cstdint>
#include <unordered_map>

namespace slambox {

namespace {

struct Edge {
  int x0, y0, x1, y1;  ///< lattice vertices [cells]
  bool used = false;
};

std::int64_t Key(int x, int y, int width) { return static_cast<std::int64_t>(y) * (width + 1) + x; }

// Turn from direction a to b: +1 left, 0 straight, -1 right (cross product sign).
int Turn(int ax, int ay, int bx, int by) {
  const int c = ax * by - ay * bx;
  return (c > 0) - (c < 0);
}

}  // namespace

std::vector<Contour> OccupiedContours(const OccupancyGrid& g, int occupied_above) {
  auto occupied = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < g.width && y < g.height &&
           g.cells[static_cast<std::size_t>(y) * g.width + x] > occupied_above;
  };
  std::vector<Edge> edges;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      if (!occupied(x, y)) continue;
      // Counter-clockwise around the cell: occupied on the left of each directed side.
      if (!occupied(x, y - 1)) edges.push_back({x, y, x + 1, y});
      if (!occupied(x + 1, y)) edges.push_back({x + 1, y, x + 1, y + 1});
      if (!occupied(x, y + 1)) edges.push_back({x + 1, y + 1, x, y + 1});
      if (!occupied(x - 1, y)) edges.push_back({x, y + 1, x, y});
    }
  // At most two edges leave a lattice vertex (two only where occupied cells touch diagonally).
  std::unordered_map<std::int64_t, std::vector<int>> leaving;
  leaving.reserve(edges.size());
  for (int i = 0; i < static_cast<int>(edges.size()); ++i)
    leaving[Key(edges[i].x0, edges[i].y0, g.width)].push_back(i);

  std::vector<Contour> contours;
  for (int start = 0; start < static_cast<int>(edges.size()); ++start) {
    if (edges[start].used) continue;
    std::vector<Eigen::Vector2i> corners;  // lattice vertices where the direction changes
    int e = start;
    int first_dx = edges[start].x1 - edges[start].x0, first_dy = edges[start].y1 - edges[start].y0;
    int dx = first_dx, dy = first_dy;
    for (;;) {
      edges[e].used = true;
      const auto& out = leaving[Key(edges[e].x1, edges[e].y1, g.width)];
      int next = -1, best_turn = -2;
      for (int candidate : out) {
        if (edges[candidate].used && candidate != start) continue;
        const int t = Turn(dx, dy, edges[candidate].x1 - edges[candidate].x0, edges[candidate].y1 - edges[candidate].y0);
        if (t > best_turn) {  // prefer the left turn: keeps diagonal neighbours' loops apart
          best_turn = t;
          next = candidate;
        }
      }
      assert(next >= 0 && "the edges of occupied cells always close");
      const int ndx = edges[next].x1 - edges[next].x0, ndy = edges[next].y1 - edges[next].y0;
      if (ndx != dx || ndy != dy) corners.emplace_back(edges[e].x1, edges[e].y1);
      if (next == start) break;
      e = next;
      dx = ndx;
      dy = ndy;
    }
    Contour c;
    c.reserve(corners.size());
    for (const auto& v : corners) c.push_back(g.origin_m + g.resolution_m * v.cast<double>());
    contours.push_back(std::move(c));
  }
  return contours;
}

double ContourArea(const Contour& c) {
  double twice = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const auto& a = c[i];
    const auto& b = c[(i + 1) % c.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

}  // namespace slambox
