#include "objscan/io/canvas.h"

#include <algorithm>
#include <cmath>

#include "objscan/io/png.h"

namespace objscan::io {
namespace {

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 7;
constexpr int kGlyphAdvance = 6;  // one column of spacing
constexpr int kLineAdvance = 9;   // two rows of spacing

// 5x7 glyphs for printable ASCII (32..126); each row's low 5 bits, bit 4 = leftmost column.
constexpr std::uint8_t kFont[95][kGlyphHeight] = {
#include "objscan/io/font5x7.inc"
};

std::uint8_t Clamp255(double v) { return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L)); }

}  // namespace

WorldToPixel::WorldToPixel(const geometry::Aabb3& box_world, double metres_per_pixel, int margin_px)
    : min_x_m_(box_world.min_m.x()), max_y_m_(box_world.max_m.y()), metres_per_pixel_(metres_per_pixel) {
  origin_px_ = Eigen::Vector2d(margin_px, margin_px);
  const Eigen::Vector3d size = box_world.Size();
  width_px_ = static_cast<int>(std::ceil(size.x() / metres_per_pixel)) + 2 * margin_px;
  height_px_ = static_cast<int>(std::ceil(size.y() / metres_per_pixel)) + 2 * margin_px;
}

WorldToPixel WorldToPixel::Scaled(double factor) const {
  WorldToPixel m = *this;
  m.metres_per_pixel_ /= factor;
  m.origin_px_ *= factor;
  m.width_px_ = static_cast<int>(std::lround(width_px_ * factor));
  m.height_px_ = static_cast<int>(std::lround(height_px_ * factor));
  return m;
}

WorldToPixel WorldToPixel::Shifted(const Eigen::Vector2d& offset_px) const {
  WorldToPixel m = *this;
  m.origin_px_ += offset_px;
  return m;
}

Canvas::Canvas(int width_px, int height_px, Rgb background)
    : width_(std::max(width_px, 0)), height_(std::max(height_px, 0)) {
  rgb_.resize(static_cast<std::size_t>(width_) * height_ * 3);
  Fill(background);
}

Rgb Canvas::Pixel(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return {0, 0, 0};
  const std::size_t i = (static_cast<std::size_t>(y) * width_ + x) * 3;
  return {rgb_[i], rgb_[i + 1], rgb_[i + 2]};
}

void Canvas::SetPixel(int x, int y, Rgb color) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  const std::size_t i = (static_cast<std::size_t>(y) * width_ + x) * 3;
  rgb_[i] = color[0];
  rgb_[i + 1] = color[1];
  rgb_[i + 2] = color[2];
}

void Canvas::BlendPixel(int x, int y, Rgb color, double alpha) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_ || alpha <= 0.0) return;
  alpha = std::min(alpha, 1.0);
  const std::size_t i = (static_cast<std::size_t>(y) * width_ + x) * 3;
  for (int k = 0; k < 3; ++k) rgb_[i + k] = Clamp255(rgb_[i + k] * (1.0 - alpha) + color[k] * alpha);
}

void Canvas::Fill(Rgb color) {
  for (std::size_t i = 0; i < rgb_.size(); i += 3) {
    rgb_[i] = color[0];
    rgb_[i + 1] = color[1];
    rgb_[i + 2] = color[2];
  }
}

void Canvas::FillRect(int x0, int y0, int x1, int y1, Rgb color) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, width_);
  y1 = std::min(y1, height_);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) SetPixel(x, y, color);
  }
}

void Canvas::DrawRect(int x0, int y0, int x1, int y1, Rgb color, int width_px) {
  FillRect(x0, y0, x1, y0 + width_px, color);
  FillRect(x0, y1 - width_px, x1, y1, color);
  FillRect(x0, y0, x0 + width_px, y1, color);
  FillRect(x1 - width_px, y0, x1, y1, color);
}

void Canvas::FillTriangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, Rgb color) {
  FillPolygon({a, b, c}, color);
}

void Canvas::FillPolygon(const std::vector<Eigen::Vector2d>& points, Rgb color) {
  if (points.size() < 3) return;
  double min_y = points[0].y(), max_y = points[0].y();
  for (const auto& p : points) {
    min_y = std::min(min_y, p.y());
    max_y = std::max(max_y, p.y());
  }
  const int y_begin = std::max(0, static_cast<int>(std::ceil(min_y - 0.5)));
  const int y_end = std::min(height_ - 1, static_cast<int>(std::floor(max_y - 0.5)));
  std::vector<double> crossings;
  // Scanline fill at pixel centres (y + 0.5) with the even-odd rule.
  for (int y = y_begin; y <= y_end; ++y) {
    const double yc = y + 0.5;
    crossings.clear();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d& p = points[i];
      const Eigen::Vector2d& q = points[(i + 1) % points.size()];
      if ((p.y() <= yc) == (q.y() <= yc)) continue;
      crossings.push_back(p.x() + (yc - p.y()) * (q.x() - p.x()) / (q.y() - p.y()));
    }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t i = 0; i + 1 < crossings.size(); i += 2) {
      const int x0 = std::max(0, static_cast<int>(std::ceil(crossings[i] - 0.5)));
      const int x1 = std::min(width_ - 1, static_cast<int>(std::floor(crossings[i + 1] - 0.5)));
      for (int x = x0; x <= x1; ++x) SetPixel(x, y, color);
    }
  }
}

void Canvas::DrawLine(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color, double width_px) {
  const double r = std::max(width_px, 0.5) / 2.0;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min(a.x(), b.x()) - r - 1)));
  const int x1 = std::min(width_ - 1, static_cast<int>(std::ceil(std::max(a.x(), b.x()) + r + 1)));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min(a.y(), b.y()) - r - 1)));
  const int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(std::max(a.y(), b.y()) + r + 1)));
  const Eigen::Vector2d d = b - a;
  const double len2 = d.squaredNorm();
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Eigen::Vector2d p(x + 0.5, y + 0.5);
      const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
      const double dist = (p - (a + t * d)).norm();
      // Coverage ramps over one pixel at the border for smooth edges.
      BlendPixel(x, y, color, std::clamp(r + 0.5 - dist, 0.0, 1.0));
    }
  }
}

void Canvas::DrawPolyline(const std::vector<Eigen::Vector2d>& points, Rgb color, double width_px) {
  for (std::size_t i = 0; i + 1 < points.size(); ++i) DrawLine(points[i], points[i + 1], color, width_px);
}

void Canvas::FillCircle(const Eigen::Vector2d& center, double radius_px, Rgb color) {
  const int x0 = std::max(0, static_cast<int>(std::floor(center.x() - radius_px - 1)));
  const int x1 = std::min(width_ - 1, static_cast<int>(std::ceil(center.x() + radius_px + 1)));
  const int y0 = std::max(0, static_cast<int>(std::floor(center.y() - radius_px - 1)));
  const int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(center.y() + radius_px + 1)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double dist = (Eigen::Vector2d(x + 0.5, y + 0.5) - center).norm();
      BlendPixel(x, y, color, std::clamp(radius_px + 0.5 - dist, 0.0, 1.0));
    }
  }
}

void Canvas::DrawCircle(const Eigen::Vector2d& center, double radius_px, Rgb color, double width_px) {
  const double half = std::max(width_px, 0.5) / 2.0;
  const int x0 = std::max(0, static_cast<int>(std::floor(center.x() - radius_px - half - 1)));
  const int x1 = std::min(width_ - 1, static_cast<int>(std::ceil(center.x() + radius_px + half + 1)));
  const int y0 = std::max(0, static_cast<int>(std::floor(center.y() - radius_px - half - 1)));
  const int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(center.y() + radius_px + half + 1)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double dist = std::abs((Eigen::Vector2d(x + 0.5, y + 0.5) - center).norm() - radius_px);
      BlendPixel(x, y, color, std::clamp(half + 0.5 - dist, 0.0, 1.0));
    }
  }
}

void Canvas::DrawArrow(const Eigen::Vector2d& from, const Eigen::Vector2d& to, Rgb color, double width_px,
                       double head_px) {
  const Eigen::Vector2d d = to - from;
  const double len = d.norm();
  if (len < 1e-9) {
    FillCircle(to, width_px, color);
    return;
  }
  const Eigen::Vector2d u = d / len;
  const Eigen::Vector2d n(-u.y(), u.x());
  const double head = std::min(head_px, len);
  const Eigen::Vector2d base = to - head * u;
  DrawLine(from, base, color, width_px);
  FillPolygon({to, base + 0.5 * head * n, base - 0.5 * head * n}, color);
}

void Canvas::DrawText(int x, int y, const std::string& text, Rgb color, int scale) {
  scale = std::max(scale, 1);
  int pen_x = x, pen_y = y;
  for (char ch : text) {
    if (ch == '\n') {
      pen_x = x;
      pen_y += kLineAdvance * scale;
      continue;
    }
    int code = static_cast<unsigned char>(ch);
    if (code < 32 || code > 126) code = '?';
    const std::uint8_t* glyph = kFont[code - 32];
    for (int row = 0; row < kGlyphHeight; ++row) {
      for (int col = 0; col < kGlyphWidth; ++col) {
        if ((glyph[row] >> (kGlyphWidth - 1 - col)) & 1) {
          FillRect(pen_x + col * scale, pen_y + row * scale, pen_x + (col + 1) * scale, pen_y + (row + 1) * scale, color);
        }
      }
    }
    pen_x += kGlyphAdvance * scale;
  }
}

int Canvas::TextWidth(const std::string& text, int scale) {
  int widest = 0, current = 0;
  for (char ch : text) {
    if (ch == '\n') {
      current = 0;
      continue;
    }
    ++current;
    widest = std::max(widest, current);
  }
  return widest == 0 ? 0 : (widest * kGlyphAdvance - 1) * std::max(scale, 1);
}

int Canvas::TextHeight(const std::string& text, int scale) {
  const int lines = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  return ((lines - 1) * kLineAdvance + kGlyphHeight) * std::max(scale, 1);
}

void Canvas::Blit(const Canvas& other, int x, int y) {
  for (int r = 0; r < other.height(); ++r) {
    for (int c = 0; c < other.width(); ++c) SetPixel(x + c, y + r, other.Pixel(c, r));
  }
}

Canvas Canvas::Downsampled(int factor) const {
  if (factor <= 1) return *this;
  Canvas out(width_ / factor, height_ / factor);
  const double inv = 1.0 / (factor * factor);
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      double sum[3] = {0, 0, 0};
      for (int dy = 0; dy < factor; ++dy) {
        const std::size_t row = (static_cast<std::size_t>(y * factor + dy) * width_ + x * factor) * 3;
        for (int dx = 0; dx < factor; ++dx) {
          for (int k = 0; k < 3; ++k) sum[k] += rgb_[row + dx * 3 + k];
        }
      }
      out.SetPixel(x, y, {Clamp255(sum[0] * inv), Clamp255(sum[1] * inv), Clamp255(sum[2] * inv)});
    }
  }
  return out;
}

void Canvas::SavePng(const std::string& path) const { WritePngRgb(path, width_, height_, rgb_); }

Rgb MixRgb(const Rgb& a, const Rgb& b, double t) {
  return {Clamp255(a[0] + (b[0] - a[0]) * t), Clamp255(a[1] + (b[1] - a[1]) * t), Clamp255(a[2] + (b[2] - a[2]) * t)};
}

Rgb ShadeRgb(const Rgb& c, double factor) {
  return {Clamp255(c[0] * factor), Clamp255(c[1] * factor), Clamp255(c[2] * factor)};
}

}  // namespace objscan::io
