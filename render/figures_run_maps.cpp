// World-frame figures of a run: trajectories over the world, each module's map, pose
// uncertainty ellipses, particle clouds and the pose graph.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "render/ellipse.hpp"
#include "render/figures_run_parts.hpp"
#include "render/world_layer.hpp"

namespace slambox::render {

std::string RunTitleSuffix(const RunFolder& run) {
  if (run.scenario.empty()) return "";
  if (run.converted_log) return " \u2014 " + run.scenario;  // a log has no seed
  return " \u2014 " + run.scenario + ", seed " + std::to_string(run.seed);
}

namespace {

std::string RunTitle(const RunFolder& run, const std::string& what) { return what + RunTitleSuffix(run); }

std::string FormatSeconds(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "t = %.1f s", t);
  return buf;
}

LegendEntry LineEntry(const SeriesStyle& s) { return {.label = s.label, .line = s.stroke}; }

void DrawPath(Canvas& c, const Axes& axes, const std::vector<StampedPose>& poses, const Stroke& stroke) {
  c.Polyline(PathPixels(axes, poses), stroke);
}

/// Points deduplicated on a half-pixel grid: identical picture, bounded size.
std::vector<Eigen::Vector2d> DedupPixels(const Axes& axes, const std::vector<Eigen::Vector2d>& pts) {
  std::set<std::pair<long, long>> seen;
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : pts) {
    if (!p.allFinite()) continue;
    const Eigen::Vector2d q = axes.ToPixel(p);
    if (q.x() < axes.area.left || q.x() > axes.area.right || q.y() < axes.area.top || q.y() > axes.area.bottom) continue;
    if (seen.insert({std::lround(q.x() * 2), std::lround(q.y() * 2)}).second) out.push_back(q);
  }
  return out;
}

void DrawGrid(Canvas& c, const Axes& axes, const OccupancyGrid& g) {
  const double res = g.resolution_m;
  for (int iy = 0; iy < g.height; ++iy)
    for (int ix = 0; ix < g.width; ++ix) {
      const int v = g.cells[static_cast<size_t>(iy) * g.width + ix];
      if (v == -1) continue;
      const double shade = 1.0 - 0.85 * std::clamp(v, 0, 100) / 100.0;  // free white, occupied near black
      if (shade > 0.985) continue;
      const Eigen::Vector2d a = axes.ToPixel(g.origin_m + Eigen::Vector2d(ix * res, iy * res));
      const Eigen::Vector2d b = axes.ToPixel(g.origin_m + Eigen::Vector2d((ix + 1) * res, (iy + 1) * res));
      c.FillRect(a.x(), b.y(), b.x(), a.y(), {shade, shade, shade, 1.0});
    }
}

}  // namespace

bool DrawTrajectoriesFigure(const RunFolder& run, const std::string& stem, const RunFolder* extent_of, double now_s,
                            const FigureOutput& out) {
  if (run.groundtruth.empty() && std::none_of(run.algorithms.begin(), run.algorithms.end(),
                                              [](const auto& a) { return !a.trajectory.empty(); }))
    return false;
  std::vector<LegendEntry> legend;
  if (!run.groundtruth.empty()) legend.push_back(LineEntry(GroundTruthStyle()));
  for (size_t i = 0; i < run.algorithms.size(); ++i)
    if (!run.algorithms[i].trajectory.empty()) legend.push_back(LineEntry(AlgorithmStyle(run, i)));
  legend.push_back({.label = "start", .line = {{}, 0.0, {}}, .marker = MarkerShape::kTriangle, .marker_color = color::kYellow});
  legend.push_back({.label = now_s >= 0 ? "now" : "end", .line = {{}, 0.0, {}}, .marker = MarkerShape::kSquare, .marker_color = Rgba{0.5, 0.5, 0.5}});
  if (run.has_world)
    for (const auto& e : WorldLegend(run.world)) legend.push_back(e);

  const auto [lo, hi] = RunExtent(extent_of ? *extent_of : run);
  WorldFigure fig(out.width_px, WorldFigureHeight(out.width_px, lo, hi, legend), lo, hi, legend, {}, out.supersample);
  if (run.has_world) DrawWorld(fig.canvas, fig.axes, run.world, false);
  for (size_t i = 0; i < run.algorithms.size(); ++i)
    DrawPath(fig.canvas, fig.axes, run.algorithms[i].trajectory, AlgorithmStyle(run, i).stroke);
  DrawPath(fig.canvas, fig.axes, run.groundtruth, GroundTruthStyle().stroke);  // on top: the reference
  // End markers in each path's colour, then the shared start on top.
  auto end_marker = [&](const std::vector<StampedPose>& p, const Rgba& c) {
    if (!p.empty() && p.back().pose.translation().allFinite())
      DrawMarker(fig.canvas, fig.axes.ToPixel(p.back().pose.translation()), MarkerShape::kSquare, 12.0, c);
  };
  end_marker(run.groundtruth, color::kGroundTruth);
  for (size_t i = 0; i < run.algorithms.size(); ++i)
    end_marker(run.algorithms[i].trajectory, AlgorithmStyle(run, i).stroke.color);
  const auto& start_src = !run.groundtruth.empty() ? run.groundtruth : run.algorithms.front().trajectory;
  if (!start_src.empty())
    DrawMarker(fig.canvas, fig.axes.ToPixel(start_src.front().pose.translation()), MarkerShape::kTriangle, 18.0, color::kYellow);
  fig.Finish(RunTitle(run, "Trajectories") + (now_s >= 0 ? ", " + FormatSeconds(now_s) : ""), legend);
  SaveFigure(fig.canvas, stem, out.svg);
  return true;
}

bool DrawMapFigure(const RunFolder& run, size_t algo, const std::string& stem, const FigureOutput& out) {
  const AlgorithmResult& a = run.algorithms.at(algo);
  if (!a.estimate) return false;
  const Estimate& e = *a.estimate;
  const bool grid = e.grid && e.grid->width > 0 && e.grid->height > 0 &&
                    e.grid->cells.size() == static_cast<size_t>(e.grid->width) * e.grid->height;
  if (e.map_points.empty() && e.landmarks.empty() && !grid) return false;
  const SeriesStyle style = AlgorithmStyle(run, algo);
  const Rgba c = style.stroke.color;
  std::vector<LegendEntry> legend;
  if (!run.world.wall_segments.empty() || !run.world.wall_circles.empty())
    legend.push_back({.label = "true walls", .line = {Rgba{0.72, 0.72, 0.72}, 1.5, {}}});
  if (grid) legend.push_back({.label = "occupancy (dark = occupied)", .line = {{}, 0.0, {}}, .patch = Rgba{0.3, 0.3, 0.3}});
  if (!e.map_points.empty()) legend.push_back({.label = "LIDAR points", .line = {{}, 0.0, {}}, .marker = MarkerShape::kCircle, .marker_color = c});
  if (!e.landmarks.empty()) {
    legend.push_back({.label = "landmark estimate", .line = {{}, 0.0, {}}, .marker = MarkerShape::kCross, .marker_color = c});
    legend.push_back({.label = "2\u03c3 ellipse", .line = {c, 1.6, {}}});
    if (run.has_world && !run.world.landmarks.empty())
      legend.push_back({.label = "true posts", .line = {{}, 0.0, {}}, .marker = MarkerShape::kRing, .marker_color = color::kBlack});
  }
  legend.push_back({.label = "estimated path", .line = {c.WithAlpha(0.45), 1.5, {}}});

  const auto [lo, hi] = RunExtent(run, static_cast<int>(algo));
  WorldFigure fig(out.width_px, WorldFigureHeight(out.width_px, lo, hi, legend), lo, hi, legend, {}, out.supersample);
  if (grid) DrawGrid(fig.canvas, fig.axes, *e.grid);
  if (run.has_world) DrawWorld(fig.canvas, fig.axes, run.world, true);
  DrawPath(fig.canvas, fig.axes, a.trajectory.empty() ? PosesOf(e) : a.trajectory, {c.WithAlpha(0.45), 1.5, {}});
  for (const auto& q : DedupPixels(fig.axes, e.map_points)) fig.canvas.FillCircle(q, 1.1, c);
  for (const auto& l : e.landmarks) {
    if (!l.position.allFinite()) continue;
    if (l.has_covariance) {
      std::vector<Eigen::Vector2d> px;
      for (const auto& p : CovarianceEllipse(l.position, l.covariance, 2.0, 96)) px.push_back(fig.axes.ToPixel(p));
      if (!px.empty()) {
        fig.canvas.FillPolygon(px, c.WithAlpha(0.12));
        px.push_back(px.front());
        fig.canvas.Polyline(px, {c, 1.6, {}});
      }
    }
    DrawMarker(fig.canvas, fig.axes.ToPixel(l.position), MarkerShape::kCross, 9.0, c);
  }
  if (run.has_world)  // true posts last, as open rings, so the estimates show through
    for (const auto& l : run.world.landmarks)
      DrawMarker(fig.canvas, fig.axes.ToPixel(l.position), MarkerShape::kRing, 12.0, color::kBlack);
  fig.Finish(RunTitle(run, "Map built by " + a.name), legend);
  SaveFigure(fig.canvas, stem, out.svg);
  return true;
}

bool DrawUncertaintyFigure(const RunFolder& run, size_t algo, const std::string& stem) {
  const AlgorithmResult& a = run.algorithms.at(algo);
  if (!a.estimate) return false;
  std::vector<const PoseEstimate*> with_cov;
  for (const auto& p : a.estimate->trajectory)
    if (p.has_covariance && p.covariance.allFinite()) with_cov.push_back(&p);
  if (with_cov.size() < 2) return false;
  const SeriesStyle style = AlgorithmStyle(run, algo);
  const Rgba c = style.stroke.color;
  const Stroke gt_stroke{color::kGroundTruth.WithAlpha(0.6), 1.6, {}};
  std::vector<LegendEntry> legend{{.label = "ground truth", .line = gt_stroke}, {.label = a.name + " estimate", .line = {c, 2.0, {}}},
                                  {.label = "2\u03c3 position ellipse", .line = {c, 1.4, {}}, .patch = c.WithAlpha(0.15)}};
  const auto [lo, hi] = RunExtent(run, static_cast<int>(algo));
  WorldFigure fig(kFigureWidthPx, WorldFigureHeight(kFigureWidthPx, lo, hi, legend), lo, hi, legend);
  if (run.has_world) DrawWorld(fig.canvas, fig.axes, run.world, true);
  DrawPath(fig.canvas, fig.axes, run.groundtruth, gt_stroke);
  DrawPath(fig.canvas, fig.axes, PosesOf(*a.estimate), {c, 2.0, {}});
  // About 30 ellipses, evenly spaced in time along the path. Ellipses larger than a
  // tenth of the view are outlined only: overlapping fills would hide everything.
  const double view_px = std::min(fig.axes.area.right - fig.axes.area.left, fig.axes.area.bottom - fig.axes.area.top);
  const size_t count = std::min<size_t>(30, with_cov.size());
  for (size_t k = 0; k < count; ++k) {
    const PoseEstimate& p = *with_cov[k * (with_cov.size() - 1) / std::max<size_t>(1, count - 1)];
    std::vector<Eigen::Vector2d> px;
    for (const auto& q : CovarianceEllipse(p.pose.translation(), p.covariance.topLeftCorner<2, 2>(), 2.0, 96))
      px.push_back(fig.axes.ToPixel(q));
    if (px.empty()) continue;
    Eigen::Vector2d lo = px[0], hi = px[0];
    for (const auto& q : px) { lo = lo.cwiseMin(q); hi = hi.cwiseMax(q); }
    if ((hi - lo).maxCoeff() < 0.1 * view_px) fig.canvas.FillPolygon(px, c.WithAlpha(0.15));
    px.push_back(px.front());
    fig.canvas.Polyline(px, {c, 1.4, {}});
  }
  fig.Finish(RunTitle(run, "Pose uncertainty of " + a.name), legend);
  SaveFigure(fig.canvas, stem);
  return true;
}

bool DrawParticlesFigure(const RunFolder& run, size_t algo, const std::string& stem) {
  const AlgorithmResult& a = run.algorithms.at(algo);
  if (!a.estimate || a.estimate->particles.empty()) return false;
  const auto& snaps = a.estimate->particles;
  // Up to 5 snapshots evenly chosen from those recorded.
  std::vector<size_t> chosen;
  const size_t n = std::min<size_t>(5, snaps.size());
  for (size_t k = 0; k < n; ++k) chosen.push_back(n == 1 ? 0 : k * (snaps.size() - 1) / (n - 1));
  std::vector<LegendEntry> legend{LineEntry(GroundTruthStyle())};
  for (size_t k = 0; k < chosen.size(); ++k)
    legend.push_back({.label = "particles, " + FormatSeconds(snaps[chosen[k]].t_s), .line = {{}, 0.0, {}},
                      .marker = MarkerShape::kCircle, .marker_color = SeriesColor(static_cast<int>(k))});
  const auto [lo, hi] = RunExtent(run, static_cast<int>(algo));
  WorldFigure fig(kFigureWidthPx, WorldFigureHeight(kFigureWidthPx, lo, hi, legend), lo, hi, legend);
  if (run.has_world) DrawWorld(fig.canvas, fig.axes, run.world, true);
  DrawPath(fig.canvas, fig.axes, run.groundtruth, GroundTruthStyle().stroke);
  for (size_t k = 0; k < chosen.size(); ++k) {
    const ParticleSnapshot& s = snaps[chosen[k]];
    const Rgba c = SeriesColor(static_cast<int>(k));
    // Each particle: a dot plus a short heading tick.
    for (const auto& p : s.poses) {
      if (!p.translation().allFinite()) continue;
      const Eigen::Vector2d q = fig.axes.ToPixel(p.translation());
      const Eigen::Vector2d h = q + 7.0 * Eigen::Vector2d(std::cos(p.theta), -std::sin(p.theta));
      fig.canvas.Line(q, h, {c.WithAlpha(0.7), 1.0, {}});
      fig.canvas.FillCircle(q, 2.2, c.WithAlpha(0.7));
    }
  }
  fig.Finish(RunTitle(run, "Particles of " + a.name), legend);
  SaveFigure(fig.canvas, stem);
  return true;
}

bool DrawPoseGraphFigure(const RunFolder& run, size_t algo, const std::string& stem) {
  const AlgorithmResult& a = run.algorithms.at(algo);
  if (!a.estimate || a.estimate->pose_graph.nodes.size() < 2) return false;
  const PoseGraphView& g = a.estimate->pose_graph;
  const Rgba odo{0.45, 0.45, 0.45}, accepted = color::kBluishGreen, rejected = color::kVermillion;
  size_t n_acc = 0, n_rej = 0;
  for (const auto& e : g.edges) {
    n_acc += e.loop_closure && e.accepted;
    n_rej += e.loop_closure && !e.accepted;
  }
  std::vector<LegendEntry> legend{
      {.label = "nodes (optimized poses)", .line = {{}, 0.0, {}}, .marker = MarkerShape::kCircle, .marker_color = color::kBlue},
      {.label = "odometry edges", .line = {odo, 1.4, {}}},
      {.label = "loop closures accepted (" + std::to_string(n_acc) + ")", .line = {accepted, 2.0, {}},
       .marker = MarkerShape::kRing, .marker_color = accepted},
      {.label = "loop closures rejected (" + std::to_string(n_rej) + ")", .line = {rejected, 2.0, {8, 5}},
       .marker = MarkerShape::kRing, .marker_color = rejected}};
  const auto [lo, hi] = RunExtent(run, static_cast<int>(algo));
  WorldFigure fig(kFigureWidthPx, WorldFigureHeight(kFigureWidthPx, lo, hi, legend), lo, hi, legend);
  if (run.has_world) DrawWorld(fig.canvas, fig.axes, run.world, true);
  auto node_px = [&](int i) { return fig.axes.ToPixel(g.nodes.at(static_cast<size_t>(i)).translation()); };
  const int n = static_cast<int>(g.nodes.size());
  auto valid = [&](const PoseGraphView::Edge& e) { return e.from >= 0 && e.to >= 0 && e.from < n && e.to < n; };
  for (const auto& e : g.edges)
    if (valid(e) && !e.loop_closure) fig.canvas.Line(node_px(e.from), node_px(e.to), {odo, 1.4, {}});
  for (const auto& e : g.edges)  // rejected under accepted, so accepted ones stay visible
    if (valid(e) && e.loop_closure && !e.accepted) fig.canvas.Line(node_px(e.from), node_px(e.to), {rejected, 1.6, {8, 5}});
  for (const auto& e : g.edges)
    if (valid(e) && e.loop_closure && e.accepted) fig.canvas.Line(node_px(e.from), node_px(e.to), {accepted, 2.0, {}});
  // A closure between revisits of one place is nearly zero-length: ring its end nodes.
  for (const auto& e : g.edges)
    if (valid(e) && e.loop_closure)
      for (int k : {e.from, e.to}) DrawMarker(fig.canvas, node_px(k), MarkerShape::kRing, 11.0, e.accepted ? accepted : rejected);
  for (int i = 0; i < n; ++i) fig.canvas.FillCircle(node_px(i), 2.6, color::kBlue);
  fig.Finish(RunTitle(run, "Pose graph of " + a.name), legend);
  SaveFigure(fig.canvas, stem);
  return true;
}

}  // namespace slambox::render
