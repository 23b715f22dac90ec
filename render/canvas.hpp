#pragma once
// A figure canvas: OpenGL drawing into an OSMesa off-screen buffer (no display, no GPU;
// Mesa's llvmpipe rasterizes), supersampled k x k then box-filtered down for antialiasing.
// Every drawing call is also recorded as SVG, so the .png and the .svg of a figure have
// identical geometry. Coordinates are output pixels, x right, y down, (0, 0) = top-left
// corner of the top-left pixel. One canvas per thread at a time is current in GL.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "render/palette.hpp"
#include "render/png_io.hpp"
#include "render/text.hpp"

namespace slambox::render {

struct Stroke {
  Rgba color = color::kBlack;
  double width_px = 1.5;
  std::vector<double> dash_px;  ///< on, off, on, ... lengths [px]; empty = solid
};

enum class HAlign { kLeft, kCenter, kRight };
enum class VAlign { kBaseline, kMiddle, kTop, kBottom };  ///< kMiddle centres the cap height

struct TextStyle {
  double size_px = 14.0;
  Rgba color = color::kBlack;
  HAlign h = HAlign::kLeft;
  VAlign v = VAlign::kBaseline;
  bool vertical = false;  ///< rotated 90 degrees counter-clockwise (reads bottom to top)
  FontWeight weight = FontWeight::kRegular;
};

class Canvas {
 public:
  /// Throws std::runtime_error when OSMesa cannot create a context of this size.
  Canvas(int width_px, int height_px, int supersample = 3, Rgba background = color::kWhite);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }

  /// Stroked polyline with round joins and caps; a translucent stroke is blended once
  /// per pixel even where it overlaps itself (stencil test).
  void Polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke);
  void Line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Stroke& stroke) { Polyline({a, b}, stroke); }
  /// Filled convex polygon.
  void FillPolygon(const std::vector<Eigen::Vector2d>& convex, const Rgba& fill);
  void FillRect(double x0, double y0, double x1, double y1, const Rgba& fill);
  void FillCircle(const Eigen::Vector2d& center, double radius_px, const Rgba& fill);
  /// Text anchored at (x, y) per style (real glyphs, FreeType).
  void Text(double x, double y, const std::string& text, const TextStyle& style);

  /// Restricts drawing to the rectangle until ResetClip().
  void SetClip(double x0, double y0, double x1, double y1);
  void ResetClip();

  /// Resolves the supersampled buffer into the output image.
  Image Finish();
  /// The SVG document of everything drawn so far.
  std::string Svg() const;

  /// Vertices of a circle polygon fine enough for this canvas' resolution.
  std::vector<Eigen::Vector2d> CirclePoints(const Eigen::Vector2d& center, double radius_px) const;

 private:
  struct Gl;
  void MakeCurrent();
  void DrawTriangles(const std::vector<Eigen::Vector2d>& triangles, const Rgba& color);
  void SvgStrokeAttributes(const Stroke& stroke);

  int width_ = 0, height_ = 0, supersample_ = 1;
  std::unique_ptr<Gl> gl_;
  std::string svg_;
  int clip_count_ = 0;
  bool clip_open_ = false;
};

/// Writes `canvas` to `path_stem`.png and, unless `svg` is false, `path_stem`.svg (atomically).
void SaveFigure(Canvas& canvas, const std::string& path_stem, bool svg = true);

}  // namespace slambox::render
