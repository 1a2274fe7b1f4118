#pragma once
// A small RGB raster canvas for top views, trajectories and plots: filled triangles and polygons,
// thick lines, circles, arrows and text in a built-in 5x7 bitmap font, saved as PNG. Pixel
// coordinates are doubles with (0, 0) the top-left corner of the top-left pixel; WorldToPixel maps a
// world XY box onto the canvas (X right, Y up).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "objscan/geometry/aabb.h"

namespace objscan::io {

using Rgb = std::array<std::uint8_t, 3>;

// World XY (metres) -> pixel coordinates for a box of the world at a fixed metres-per-pixel,
// with a border of margin_px around it and an optional offset of the whole map on the canvas.
class WorldToPixel {
 public:
  WorldToPixel() = default;
  // Maps [min.x, max.x] x [min.y, max.y] of `box_world` (z ignored).
  WorldToPixel(const geometry::Aabb3& box_world, double metres_per_pixel, int margin_px);

  Eigen::Vector2d ToPixel(double x_m, double y_m) const {
    return {origin_px_.x() + (x_m - min_x_m_) / metres_per_pixel_, origin_px_.y() + (max_y_m_ - y_m) / metres_per_pixel_};
  }
  Eigen::Vector2d ToPixel(const Eigen::Vector3d& p_world) const { return ToPixel(p_world.x(), p_world.y()); }
  Eigen::Vector2d ToWorld(const Eigen::Vector2d& pixel) const {
    return {min_x_m_ + (pixel.x() - origin_px_.x()) * metres_per_pixel_,
            max_y_m_ - (pixel.y() - origin_px_.y()) * metres_per_pixel_};
  }
  double metres_per_pixel() const { return metres_per_pixel_; }
  double PixelsPerMetre() const { return 1.0 / metres_per_pixel_; }
  // Size of the mapped box plus margins.
  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }
  // The same mapping on a canvas scaled by `factor` (for supersampling) or shifted by `offset_px`.
  WorldToPixel Scaled(double factor) const;
  WorldToPixel Shifted(const Eigen::Vector2d& offset_px) const;

 private:
  double min_x_m_ = 0, max_y_m_ = 0;
  double metres_per_pixel_ = 0.01;
  Eigen::Vector2d origin_px_ = Eigen::Vector2d::Zero();
  int width_px_ = 0, height_px_ = 0;
};

class Canvas {
 public:
  Canvas() = default;
  Canvas(int width_px, int height_px, Rgb background = {255, 255, 255});

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<std::uint8_t>& rgb() const { return rgb_; }
  Rgb Pixel(int x, int y) const;

  // Pixel writes outside the canvas are ignored everywhere.
  void SetPixel(int x, int y, Rgb color);
  // color * alpha + current * (1 - alpha), alpha in [0, 1].
  void BlendPixel(int x, int y, Rgb color, double alpha);
  void Fill(Rgb color);
  // Pixels [x0, x1) x [y0, y1).
  void FillRect(int x0, int y0, int x1, int y1, Rgb color);
  void DrawRect(int x0, int y0, int x1, int y1, Rgb color, int width_px = 1);
  // Pixels whose centres lie inside the triangle / polygon (even-odd rule).
  void FillTriangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, Rgb color);
  void FillPolygon(const std::vector<Eigen::Vector2d>& points, Rgb color);
  // A line of the given width with round caps, anti-aliased at its border.
  void DrawLine(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color, double width_px = 1.0);
  void DrawPolyline(const std::vector<Eigen::Vector2d>& points, Rgb color, double width_px = 1.0);
  void FillCircle(const Eigen::Vector2d& center, double radius_px, Rgb color);
  void DrawCircle(const Eigen::Vector2d& center, double radius_px, Rgb color, double width_px = 1.0);
  // A line from `from` to `to` with a filled head of length head_px at `to`.
  void DrawArrow(const Eigen::Vector2d& from, const Eigen::Vector2d& to, Rgb color, double width_px = 1.0,
                 double head_px = 8.0);
  // Text in the 5x7 font, each font pixel drawn as scale x scale pixels; (x, y) is the top-left
  // corner. '\n' starts a new line. Characters outside printable ASCII are drawn as '?'.
  void DrawText(int x, int y, const std::string& text, Rgb color, int scale = 1);
  static int TextWidth(const std::string& text, int scale = 1);
  static int TextHeight(const std::string& text, int scale = 1);
  // Copies `other` with its top-left corner at (x, y).
  void Blit(const Canvas& other, int x, int y);
  // Box-filters the canvas down by an integer factor (used for anti-aliased supersampled drawing).
  Canvas Downsampled(int factor) const;

  // Throws InputError naming the path on failure (atomic write).
  void SavePng(const std::string& path) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> rgb_;
};

// Mixes two colours: a * (1 - t) + b * t.
Rgb MixRgb(const Rgb& a, const Rgb& b, double t);
// Scales a colour's brightness (clamped).
Rgb ShadeRgb(const Rgb& c, double factor);

}  // namespace objscan::io
