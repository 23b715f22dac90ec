#pragma once
// Shared pieces of the world-frame figures: the equal-aspect map axes with the legend
// outside on the right, the true world (walls, posts, movers' paths), and one consistent
// colour / dash per module across every figure of a run.
#include <string>
#include <vector>

#include "render/legend.hpp"
#include "render/run_folder.hpp"

namespace slambox::render {

struct SeriesStyle {
  std::string label;
  Stroke stroke;
};

/// Module i of a run: a baseline (metrics.json's `modules`, ModuleInfo::baseline) is
/// orange and dashed, the others take the Okabe-Ito series colours in metrics.json order.
SeriesStyle AlgorithmStyle(const RunFolder& run, size_t index);
SeriesStyle GroundTruthStyle();

/// A world-frame figure: canvas, equal-aspect axes that contain `lo`..`hi` with a margin,
/// and space on the right for a legend of `legend` entries.
struct WorldFigure {
  Canvas canvas;
  Axes axes;
  WorldFigure(int width_px, int height_px, Eigen::Vector2d lo, Eigen::Vector2d hi,
              const std::vector<LegendEntry>& legend, const FigureStyle& style = {}, int supersample = 3);
  /// Frame, labels "x [m]" / "y [m]", title, scale bar and the legend.
  void Finish(const std::string& title, const std::vector<LegendEntry>& legend, const FigureStyle& style = {});
};

/// A canvas height [px] that fits the world's aspect ratio at `width_px` (in 480..1100).
int WorldFigureHeight(int width_px, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                      const std::vector<LegendEntry>& legend, const FigureStyle& style = {});

/// The region shown for a run: the world, ground truth and, within a margin of 50% of
/// that extent, the estimated trajectories (a diverged estimate does not shrink the map).
/// Without world and ground truth (a converted log) the estimates' paths, map points and
/// occupied grid cells, so the figure fits the map. `only_algo` >= 0 limits the
/// estimates considered to that module (its own figures).
std::pair<Eigen::Vector2d, Eigen::Vector2d> RunExtent(const RunFolder& run, int only_algo = -1);

/// Walls (segments, circles), true posts and movers' paths; `faint` for backgrounds.
void DrawWorld(Canvas& canvas, const Axes& axes, const World& world, bool faint);
/// Legend entries describing what DrawWorld drew (only kinds present in the world).
std::vector<LegendEntry> WorldLegend(const World& world);

std::vector<Eigen::Vector2d> PathPixels(const Axes& axes, const std::vector<StampedPose>& poses);
std::vector<StampedPose> PosesOf(const Estimate& estimate);

}  // namespace slambox::render
