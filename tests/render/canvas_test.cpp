// Pixel-level checks of the off-screen renderer: geometry lands where the axes say, text
// is drawn, ticks are round, ellipses match their covariance, SVG agrees with PNG, and
// rendering is deterministic.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <regex>
#include <sstream>

#include "render/axes.hpp"
#include "render/canvas.hpp"
#include "render/ellipse.hpp"
#include "render/legend.hpp"

namespace slambox::render {
namespace {

bool IsBackground(const Image& img, int x, int y) {
  const auto* p = img.At(x, y);
  return p[0] > 245 && p[1] > 245 && p[2] > 245;
}

TEST(Canvas, LineBetweenWorldPointsLandsOnExpectedPixels) {
  Canvas canvas(120, 80, 3);
  const Axes axes = MakeAxes({10, 10, 110, 70}, {0.0, 10.0}, {0.0, 6.0});
  // World (1, 3) -> (9, 3): y = 3 is pixel row 70 - 3 * 10 = 40; x from 20 to 100.
  canvas.Line(axes.ToPixel(1.0, 3.0), axes.ToPixel(9.0, 3.0), {color::kBlack, 2.0, {}});
  const Image img = canvas.Finish();
  for (int x = 22; x <= 97; ++x) {
    EXPECT_LT(img.At(x, 39)[0], 40) << "x=" << x;  // rows 39 and 40 straddle y = 40
    EXPECT_LT(img.At(x, 40)[0], 40) << "x=" << x;
    EXPECT_TRUE(IsBackground(img, x, 36));
    EXPECT_TRUE(IsBackground(img, x, 43));
  }
  EXPECT_TRUE(IsBackground(img, 17, 40));   // before the start (round cap radius 1)
  EXPECT_TRUE(IsBackground(img, 103, 40));  // after the end
}

TEST(Canvas, DiagonalWorldLineFollowsTheMapping) {
  Canvas canvas(100, 100, 2);
  const Axes axes = MakeEqualAspectAxes({0, 0, 100, 100}, {0.0, 0.0}, {10.0, 10.0});
  canvas.Line(axes.ToPixel(0.0, 0.0), axes.ToPixel(10.0, 10.0), {color::kBlack, 3.0, {}});
  const Image img = canvas.Finish();
  for (int i = 5; i < 95; i += 5) EXPECT_LT(img.At(i, 99 - i)[0], 60) << i;  // y flips: world up = pixel up
  EXPECT_TRUE(IsBackground(img, 20, 20));
  EXPECT_TRUE(IsBackground(img, 80, 80));
}

TEST(Canvas, LegendTextIsDrawnInItsBox) {
  Canvas canvas(300, 200, 3);
  const Axes axes = MakeAxes({40, 20, 290, 170}, {0.0, 1.0}, {0.0, 1.0});
  const std::vector<LegendEntry> entries{{.label = "ground truth", .line = {color::kBlack, 2.0, {}}},
                                         {.label = "odometry", .line = {color::kBlue, 2.0, {6, 3}}}};
  const Eigen::Vector4d box = DrawLegend(canvas, axes, entries, {});
  const Image img = canvas.Finish();
  // Count dark pixels in the text column (right of the swatches) of each row.
  const int text_x0 = static_cast<int>(box[0]) + 10 + 34 + 8;
  const double row = FigureStyle{}.legend_px * 1.55;
  for (int i = 0; i < 2; ++i) {
    const int y0 = static_cast<int>(box[1] + 10 + row * i), y1 = static_cast<int>(y0 + row);
    int dark = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = text_x0; x < static_cast<int>(box[2]); ++x) dark += img.At(x, y)[0] < 128;
    EXPECT_GT(dark, 40) << "legend row " << i << " has no glyph pixels";
  }
  // The glyphs are wider than a bitmap block: "ground truth" spans about its layout width.
  EXPECT_NEAR(TextWidth("ground truth", 15.0), 88.0, 12.0);
}

TEST(Axes, TicksAreRoundNumbers) {
  EXPECT_DOUBLE_EQ(NiceStep(10.0, 5), 2.0);
  EXPECT_DOUBLE_EQ(NiceStep(0.93, 5), 0.2);
  EXPECT_DOUBLE_EQ(NiceStep(730.0, 6), 100.0);
  const std::vector<double> t = NiceTicks(-0.37, 2.81, 6);
  ASSERT_EQ(t.size(), 6u);
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(t[i], 0.5 * i, 1e-12);
  for (double v : NiceTicks(13.7, 912.4, 5)) EXPECT_NEAR(std::fmod(v, 200.0), 0.0, 1e-9);
  EXPECT_EQ(FormatTick(0.25, 0.05), "0.25");
  EXPECT_EQ(FormatTick(-1e-17, 0.5), "0.0");
  EXPECT_EQ(FormatTick(200.0, 100.0), "200");
  const std::vector<double> lt = LogTicks(0.3, 40.0);
  EXPECT_EQ(lt, (std::vector<double>{0.5, 1, 2, 5, 10, 20}));
  const Eigen::Vector2d r = NiceRange(0.13, 0.87);
  EXPECT_NEAR(r[0], 0.1, 1e-12);
  EXPECT_NEAR(r[1], 0.9, 1e-12);
}

TEST(Ellipse, ExtentMatchesCovariance) {
  // Rotated covariance: the k-sigma ellipse's half-extent along x is k sqrt(Sxx) and along
  // y is k sqrt(Syy) (the projection of the contour).
  Eigen::Matrix2d cov;
  cov << 4.0, 1.5, 1.5, 1.0;
  const auto pts = CovarianceEllipse({0, 0}, cov, 2.0, 720);
  double xmax = 0, ymax = 0;
  for (const auto& p : pts) {
    xmax = std::max(xmax, p.x());
    ymax = std::max(ymax, p.y());
  }
  EXPECT_NEAR(xmax, 2.0 * 2.0, 1e-3);
  EXPECT_NEAR(ymax, 2.0 * 1.0, 1e-3);
  // Every point lies on the Mahalanobis contour of radius 2.
  for (const auto& p : pts) EXPECT_NEAR(std::sqrt(p.dot(cov.inverse() * p)), 2.0, 1e-9);

  // Rendered: pixel bounding box of the filled ellipse (1 m = 10 px).
  Canvas canvas(200, 200, 3);
  const Axes axes = MakeEqualAspectAxes({0, 0, 200, 200}, {-10, -10}, {10, 10});
  std::vector<Eigen::Vector2d> px;
  for (const auto& p : CovarianceEllipse({0, 0}, cov, 2.0, 256)) px.push_back(axes.ToPixel(p));
  canvas.FillPolygon(px, color::kBlue);
  const Image img = canvas.Finish();
  int x0 = 200, x1 = -1, y0 = 200, y1 = -1;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x)
      if (img.At(x, y)[0] < 128) {
        x0 = std::min(x0, x); x1 = std::max(x1, x); y0 = std::min(y0, y); y1 = std::max(y1, y);
      }
  EXPECT_NEAR((x1 - x0 + 1) / 10.0, 2 * 4.0, 0.2);  // width 2 * 2 sqrt(4) m
  EXPECT_NEAR((y1 - y0 + 1) / 10.0, 2 * 2.0, 0.2);
  EXPECT_TRUE(CovarianceEllipse({0, 0}, -Eigen::Matrix2d::Identity()).empty());
}

void DrawScene(Canvas& canvas) {
  const Axes axes = MakeAxes({50, 30, 230, 150}, {0.0, 10.0}, {0.0, 5.0});
  DrawGrid(canvas, axes);
  canvas.Polyline({axes.ToPixel(1, 1), axes.ToPixel(4, 4), axes.ToPixel(9, 2)}, {color::kVermillion, 2.5, {}});
  canvas.FillCircle(axes.ToPixel(5, 1), 4.0, color::kBlue.WithAlpha(0.5));
  DrawFrame(canvas, axes, {"Title", "x [m]", "y [m]"});
}

TEST(Canvas, SvgAndPngAgreeOnGeometry) {
  Canvas canvas(260, 190, 3);
  DrawScene(canvas);
  const Image img = canvas.Finish();
  const std::string svg = canvas.Svg();
  // The vermillion polyline's SVG vertices: PNG pixels there and at segment midpoints are
  // vermillion-ish (red high, blue low).
  const std::regex re("<polyline fill=\"none\" points=\"([^\"]+)\" stroke=\"#d55e00\"");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, re));
  std::vector<Eigen::Vector2d> pts;
  std::stringstream ss(m[1].str());
  std::string pair;
  while (ss >> pair) {
    const auto comma = pair.find(',');
    pts.push_back({std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1))});
  }
  ASSERT_EQ(pts.size(), 3u);
  for (size_t i = 0; i + 1 < pts.size(); ++i)
    for (double f : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      const Eigen::Vector2d p = pts[i] + f * (pts[i + 1] - pts[i]);
      const auto* px = img.At(static_cast<int>(p.x()), static_cast<int>(p.y()));
      EXPECT_GT(px[0], 170) << p.transpose();
      EXPECT_LT(px[2], 90) << p.transpose();
    }
  EXPECT_NE(svg.find("<text"), std::string::npos);
  EXPECT_NE(svg.find(">x [m]</text>"), std::string::npos);
}

TEST(Canvas, RenderingTwiceIsBitIdentical) {
  Canvas a(260, 190, 3), b(260, 190, 3);
  DrawScene(a);
  DrawScene(b);
  EXPECT_EQ(EncodePng(a.Finish()), EncodePng(b.Finish()));
  EXPECT_EQ(a.Svg(), b.Svg());
}

TEST(Canvas, TranslucentPolylineBlendsOncePerPixel) {
  Canvas canvas(60, 60, 2);
  // A path crossing itself: the crossing is no darker than the rest of the stroke.
  canvas.Polyline({{10, 10}, {50, 50}, {50, 10}, {10, 50}}, {color::kBlack.WithAlpha(0.5), 4.0, {}});
  const Image img = canvas.Finish();
  EXPECT_NEAR(img.At(30, 30)[0], img.At(20, 20)[0], 3);
}

}  // namespace
}  // namespace slambox::render
