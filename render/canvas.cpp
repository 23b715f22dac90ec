#include "render/canvas.hpp"

#include <GL/gl.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/atomic_file.hpp"

namespace slambox::render {

struct Canvas::Gl {
  OSMesaContext context = nullptr;
  std::vector<std::uint8_t> buffer;  // RGBA, bottom row first (OSMesa's default)
};

namespace {
thread_local const Canvas* g_current = nullptr;

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}
std::string XmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}
std::string Points(const std::vector<Eigen::Vector2d>& pts) {
  std::string s;
  for (const auto& p : pts) s += (s.empty() ? "" : " ") + Num(p.x()) + "," + Num(p.y());
  return s;
}

/// Splits a polyline into its "on" pieces for a dash pattern (lengths along the path).
std::vector<std::vector<Eigen::Vector2d>> DashPieces(const std::vector<Eigen::Vector2d>& pts,
                                                     const std::vector<double>& dash) {
  std::vector<std::vector<Eigen::Vector2d>> pieces;
  size_t k = 0;
  double left = dash[0];  // length remaining in the current dash element
  bool on = true;
  std::vector<Eigen::Vector2d> cur{pts[0]};
  for (size_t i = 1; i < pts.size(); ++i) {
    Eigen::Vector2d a = pts[i - 1];
    const Eigen::Vector2d b = pts[i];
    double seg = (b - a).norm();
    while (seg > left) {
      const Eigen::Vector2d cut = a + (b - a) * (left / seg);
      if (on) {
        cur.push_back(cut);
        pieces.push_back(cur);
      }
      cur = {cut};
      seg -= left;
      a = cut;
      on = !on;
      k = (k + 1) % dash.size();
      left = dash[k];
    }
    left -= seg;
    if (on) cur.push_back(b);
  }
  if (on && cur.size() >= 2) pieces.push_back(cur);
  return pieces;
}
}  // namespace

Canvas::Canvas(int width_px, int height_px, int supersample, Rgba background)
    : width_(width_px), height_(height_px), supersample_(supersample), gl_(std::make_unique<Gl>()) {
  if (width_px <= 0 || height_px <= 0 || supersample < 1) throw std::runtime_error("canvas: bad size");
  gl_->context = OSMesaCreateContextExt(OSMESA_RGBA, 0, 8, 0, nullptr);
  if (!gl_->context) throw std::runtime_error("OSMesa: cannot create an off-screen GL context");
  gl_->buffer.assign(static_cast<size_t>(width_ * supersample_) * (height_ * supersample_) * 4, 0);
  MakeCurrent();
  glViewport(0, 0, width_ * supersample_, height_ * supersample_);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, width_, height_, 0, -1, 1);  // y down, in output pixels
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glClearColor(background.r, background.g, background.b, 1.0);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  svg_ = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width_) + "\" height=\"" +
         std::to_string(height_) + "\" viewBox=\"0 0 " + std::to_string(width_) + " " + std::to_string(height_) +
         "\">\n<rect width=\"100%\" height=\"100%\" fill=\"" + HexColor(background) + "\"/>\n";
}

Canvas::~Canvas() {
  if (g_current == this) g_current = nullptr;
  if (gl_ && gl_->context) OSMesaDestroyContext(gl_->context);
}

void Canvas::MakeCurrent() {
  if (g_current == this) return;
  if (!OSMesaMakeCurrent(gl_->context, gl_->buffer.data(), GL_UNSIGNED_BYTE, width_ * supersample_,
                         height_ * supersample_))
    throw std::runtime_error("OSMesa: cannot make the context current");
  g_current = this;
}

std::vector<Eigen::Vector2d> Canvas::CirclePoints(const Eigen::Vector2d& c, double r) const {
  // Chord error r (1 - cos(pi/n)) below a quarter of a supersampled pixel.
  const double r_ss = std::max(r * supersample_, 0.5);
  const int n = std::clamp(static_cast<int>(std::ceil(M_PI / std::acos(std::max(0.0, 1.0 - 0.25 / r_ss)))), 8, 256);
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    pts.push_back(c + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return pts;
}

void Canvas::DrawTriangles(const std::vector<Eigen::Vector2d>& tris, const Rgba& c) {
  MakeCurrent();
  glColor4d(c.r, c.g, c.b, c.a);
  glBegin(GL_TRIANGLES);
  for (const auto& p : tris) glVertex2d(p.x(), p.y());
  glEnd();
}

void Canvas::Polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke) {
  if (points.size() < 2 || stroke.width_px <= 0.0) return;
  svg_ += "<polyline fill=\"none\" points=\"" + Points(points) + "\"";
  SvgStrokeAttributes(stroke);
  svg_ += "/>\n";

  std::vector<std::vector<Eigen::Vector2d>> pieces;
  if (stroke.dash_px.empty()) pieces.push_back(points);
  else pieces = DashPieces(points, stroke.dash_px);
  // Quads along every segment plus a disc at every vertex (round joins and caps).
  const double h = 0.5 * stroke.width_px;
  std::vector<Eigen::Vector2d> tris;
  for (const auto& piece : pieces) {
    for (size_t i = 0; i + 1 < piece.size(); ++i) {
      const Eigen::Vector2d d = piece[i + 1] - piece[i];
      if (d.norm() < 1e-12) continue;
      const Eigen::Vector2d n = Eigen::Vector2d(-d.y(), d.x()).normalized() * h;
      const Eigen::Vector2d a0 = piece[i] + n, a1 = piece[i] - n, b0 = piece[i + 1] + n, b1 = piece[i + 1] - n;
      tris.insert(tris.end(), {a0, a1, b0, b0, a1, b1});
    }
    for (const auto& p : piece) {
      const auto ring = CirclePoints(p, h);
      for (size_t k = 0; k < ring.size(); ++k) tris.insert(tris.end(), {p, ring[k], ring[(k + 1) % ring.size()]});
    }
  }
  if (stroke.color.a >= 1.0) {
    DrawTriangles(tris, stroke.color);
    return;
  }
  // Translucent: blend each pixel once, then reset the stencil where we drew.
  MakeCurrent();
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_EQUAL, 0, 0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
  DrawTriangles(tris, stroke.color);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glStencilFunc(GL_ALWAYS, 0, 0xFF);
  glStencilOp(GL_ZERO, GL_ZERO, GL_ZERO);
  DrawTriangles(tris, stroke.color);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_STENCIL_TEST);
}

void Canvas::SvgStrokeAttributes(const Stroke& s) {
  svg_ += " stroke=\"" + HexColor(s.color) + "\" stroke-width=\"" + Num(s.width_px) +
          "\" stroke-linejoin=\"round\" stroke-linecap=\"round\"";
  if (s.color.a < 1.0) svg_ += " stroke-opacity=\"" + Num(s.color.a) + "\"";
  if (!s.dash_px.empty()) {
    svg_ += " stroke-dasharray=\"";
    for (size_t i = 0; i < s.dash_px.size(); ++i) svg_ += (i ? "," : "") + Num(s.dash_px[i]);
    svg_ += "\"";
  }
}

void Canvas::FillPolygon(const std::vector<Eigen::Vector2d>& convex, const Rgba& fill) {
  if (convex.size() < 3) return;
  svg_ += "<polygon points=\"" + Points(convex) + "\" fill=\"" + HexColor(fill) + "\"";
  if (fill.a < 1.0) svg_ += " fill-opacity=\"" + Num(fill.a) + "\"";
  svg_ += "/>\n";
  std::vector<Eigen::Vector2d> tris;
  for (size_t i = 1; i + 1 < convex.size(); ++i) tris.insert(tris.end(), {convex[0], convex[i], convex[i + 1]});
  DrawTriangles(tris, fill);
}

void Canvas::FillRect(double x0, double y0, double x1, double y1, const Rgba& fill) {
  FillPolygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, fill);
}

void Canvas::FillCircle(const Eigen::Vector2d& c, double r, const Rgba& fill) {
  svg_ += "<circle cx=\"" + Num(c.x()) + "\" cy=\"" + Num(c.y()) + "\" r=\"" + Num(r) + "\" fill=\"" + HexColor(fill) + "\"";
  if (fill.a < 1.0) svg_ += " fill-opacity=\"" + Num(fill.a) + "\"";
  svg_ += "/>\n";
  const auto ring = CirclePoints(c, r);
  std::vector<Eigen::Vector2d> tris;
  for (size_t k = 0; k < ring.size(); ++k) tris.insert(tris.end(), {c, ring[k], ring[(k + 1) % ring.size()]});
  DrawTriangles(tris, fill);
}

void Canvas::Text(double x, double y, const std::string& text, const TextStyle& st) {
  if (text.empty()) return;
  const double s = supersample_;
  const TextMask mask = RasterizeText(text, st.size_px * s, st.weight);
  // Pen start along the text direction u and baseline offset along its normal.
  const double advance = mask.advance_px / s;
  const double along = st.h == HAlign::kLeft ? 0.0 : st.h == HAlign::kCenter ? -0.5 * advance : -advance;
  const double down = st.v == VAlign::kBaseline ? 0.0
                      : st.v == VAlign::kMiddle ? 0.5 * kCapHeightEm * st.size_px
                      : st.v == VAlign::kTop    ? kCapHeightEm * st.size_px
                                                : -0.236 * st.size_px;  // DejaVu descender
  const Eigen::Vector2d u = st.vertical ? Eigen::Vector2d(0, -1) : Eigen::Vector2d(1, 0);  // reading direction
  const Eigen::Vector2d n(-u.y(), u.x());  // "down" in the text's frame
  // Pen origin snapped to the supersampled grid so glyph texels map 1:1 onto samples.
  Eigen::Vector2d pen = Eigen::Vector2d(x, y) + along * u + down * n;
  pen = (pen * s).array().round().matrix() / s;

  svg_ += "<text x=\"" + Num(pen.x()) + "\" y=\"" + Num(pen.y()) + "\" font-family=\"DejaVu Sans\" font-size=\"" +
          Num(st.size_px) + "\"" + (st.weight == FontWeight::kBold ? " font-weight=\"bold\"" : "") + " fill=\"" +
          HexColor(st.color) + "\"";
  if (st.vertical) svg_ += " transform=\"rotate(-90 " + Num(pen.x()) + " " + Num(pen.y()) + ")\"";
  svg_ += ">" + XmlEscape(text) + "</text>\n";
  if (mask.width == 0 || mask.height == 0) return;

  MakeCurrent();
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_ALPHA, mask.width, mask.height, 0, GL_ALPHA, GL_UNSIGNED_BYTE, mask.coverage.data());
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glEnable(GL_TEXTURE_2D);
  // Mask corners in the text frame (output pixels), then into the canvas.
  const double left = -mask.origin_x / s, right = (mask.width - mask.origin_x) / s;
  const double top = -mask.baseline_y / s, bottom = (mask.height - mask.baseline_y) / s;
  auto corner = [&](double a, double b) { return Eigen::Vector2d(pen + a * u + b * n); };
  glColor4d(st.color.r, st.color.g, st.color.b, st.color.a);
  glBegin(GL_QUADS);
  const Eigen::Vector2d c00 = corner(left, top), c10 = corner(right, top), c11 = corner(right, bottom),
                        c01 = corner(left, bottom);
  glTexCoord2d(0, 0); glVertex2d(c00.x(), c00.y());
  glTexCoord2d(1, 0); glVertex2d(c10.x(), c10.y());
  glTexCoord2d(1, 1); glVertex2d(c11.x(), c11.y());
  glTexCoord2d(0, 1); glVertex2d(c01.x(), c01.y());
  glEnd();
  glDisable(GL_TEXTURE_2D);
  glDeleteTextures(1, &tex);
}

void Canvas::SetClip(double x0, double y0, double x1, double y1) {
  ResetClip();
  MakeCurrent();
  const int s = supersample_;
  const int ix0 = static_cast<int>(std::floor(x0 * s)), ix1 = static_cast<int>(std::ceil(x1 * s));
  const int iy0 = static_cast<int>(std::floor(y0 * s)), iy1 = static_cast<int>(std::ceil(y1 * s));
  glEnable(GL_SCISSOR_TEST);
  glScissor(ix0, height_ * s - iy1, ix1 - ix0, iy1 - iy0);  // GL windows count rows from the bottom
  const std::string id = "clip" + std::to_string(clip_count_++);
  svg_ += "<clipPath id=\"" + id + "\"><rect x=\"" + Num(x0) + "\" y=\"" + Num(y0) + "\" width=\"" + Num(x1 - x0) +
          "\" height=\"" + Num(y1 - y0) + "\"/></clipPath>\n<g clip-path=\"url(#" + id + ")\">\n";
  clip_open_ = true;
}

void Canvas::ResetClip() {
  if (!clip_open_) return;
  MakeCurrent();
  glDisable(GL_SCISSOR_TEST);
  svg_ += "</g>\n";
  clip_open_ = false;
}

Image Canvas::Finish() {
  MakeCurrent();
  glFinish();
  const int s = supersample_, w_ss = width_ * s, h_ss = height_ * s;
  Image img;
  img.width = width_;
  img.height = height_;
  img.rgb.resize(static_cast<size_t>(width_) * height_ * 3);
  // Box filter: each output pixel is the mean of its s x s samples (row 0 of the GL
  // buffer is the bottom row).
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        int sum = 0;
        for (int dy = 0; dy < s; ++dy) {
          const int row = h_ss - 1 - (y * s + dy);
          for (int dx = 0; dx < s; ++dx) sum += gl_->buffer[(static_cast<size_t>(row) * w_ss + x * s + dx) * 4 + ch];
        }
        img.rgb[(static_cast<size_t>(y) * width_ + x) * 3 + ch] = static_cast<std::uint8_t>((sum + s * s / 2) / (s * s));
      }
  return img;
}

std::string Canvas::Svg() const { return svg_ + (clip_open_ ? "</g>\n" : "") + "</svg>\n"; }

void SaveFigure(Canvas& canvas, const std::string& path_stem, bool svg) {
  WritePng(path_stem + ".png", canvas.Finish());
  if (svg) WriteFileAtomic(path_stem + ".svg", canvas.Svg());
}

}  // namespace slambox::render
