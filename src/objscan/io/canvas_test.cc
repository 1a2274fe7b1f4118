#include "objscan/io/canvas.h"

#include <gtest/gtest.h>

#include "objscan/io/png.h"
#include "objscan/io/test_util.h"

namespace objscan::io {
namespace {

constexpr Rgb kWhite = {255, 255, 255};
constexpr Rgb kRed = {255, 0, 0};

int CountColor(const Canvas& c, const Rgb& color) {
  int n = 0;
  for (int y = 0; y < c.height(); ++y) {
    for (int x = 0; x < c.width(); ++x) n += c.Pixel(x, y) == color;
  }
  return n;
}

TEST(CanvasTest, WorldToPixelMapsCornersWithYUp) {
  geometry::Aabb3 box;
  box.Extend(Eigen::Vector3d(-1, 2, 0));
  box.Extend(Eigen::Vector3d(3, 4, 1));
  const WorldToPixel map(box, 0.01, 5);
  EXPECT_EQ(map.width_px(), 400 + 10);
  EXPECT_EQ(map.height_px(), 200 + 10);
  EXPECT_TRUE(map.ToPixel(-1, 4).isApprox(Eigen::Vector2d(5, 5)));      // top-left
  EXPECT_TRUE(map.ToPixel(3, 2).isApprox(Eigen::Vector2d(405, 205)));   // bottom-right
  EXPECT_TRUE(map.ToWorld(map.ToPixel(0.37, 2.9)).isApprox(Eigen::Vector2d(0.37, 2.9)));
  const WorldToPixel fine = map.Scaled(2);
  EXPECT_TRUE(fine.ToPixel(3, 2).isApprox(Eigen::Vector2d(810, 410)));
}

TEST(CanvasTest, FilledShapesCoverTheirArea) {
  Canvas c(100, 100, kWhite);
  c.FillRect(10, 10, 20, 30, kRed);
  EXPECT_EQ(CountColor(c, kRed), 10 * 20);
  c.Fill(kWhite);
  // Right triangle with legs 40: about 800 pixel centres inside.
  c.FillTriangle({10, 10}, {50, 10}, {10, 50}, kRed);
  EXPECT_NEAR(CountColor(c, kRed), 800, 45);
  EXPECT_EQ(c.Pixel(12, 12), kRed);
  EXPECT_EQ(c.Pixel(45, 45), kWhite);
  c.Fill(kWhite);
  // A square given as a polygon with a square hole (even-odd rule): 60^2 - 20^2 pixels.
  c.FillPolygon({{20, 20}, {80, 20}, {80, 80}, {20, 80}, {20, 20}, {40, 40}, {40, 60}, {60, 60}, {60, 40}, {40, 40}},
                kRed);
  EXPECT_EQ(CountColor(c, kRed), 3600 - 400);
  EXPECT_EQ(c.Pixel(50, 50), kWhite);
}

TEST(CanvasTest, LinesCirclesAndArrows) {
  Canvas c(100, 100, kWhite);
  c.DrawLine({10, 50.5}, {90, 50.5}, kRed, 3.0);
  EXPECT_EQ(c.Pixel(50, 50), kRed);
  EXPECT_EQ(c.Pixel(50, 49), kRed);
  EXPECT_EQ(c.Pixel(50, 51), kRed);
  EXPECT_EQ(c.Pixel(50, 46), kWhite);
  c.Fill(kWhite);
  c.FillCircle({50, 50}, 10, kRed);
  EXPECT_NEAR(CountColor(c, kRed), 3.14159 * 100, 40);
  c.Fill(kWhite);
  c.DrawArrow({10, 10}, {60, 10}, kRed, 1.0, 10.0);
  EXPECT_EQ(c.Pixel(55, 10), kRed);   // inside the head
  EXPECT_EQ(c.Pixel(52, 13), kRed);   // the head is wider than the shaft
  EXPECT_EQ(c.Pixel(30, 13), kWhite);
}

TEST(CanvasTest, TextUsesTheBitmapFont) {
  Canvas c(40, 20, kWhite);
  c.DrawText(1, 1, "I", kRed, 1);
  // 'I' is a bar of 3 on the top and bottom rows and a stem in the middle column.
  EXPECT_EQ(c.Pixel(1 + 1, 1), kRed);
  EXPECT_EQ(c.Pixel(1 + 3, 1), kRed);
  EXPECT_EQ(c.Pixel(1 + 0, 1), kWhite);
  EXPECT_EQ(c.Pixel(1 + 2, 4), kRed);
  EXPECT_EQ(c.Pixel(1 + 1, 4), kWhite);
  EXPECT_EQ(CountColor(c, kRed), 3 + 5 + 3);
  EXPECT_EQ(Canvas::TextWidth("ab", 1), 11);
  EXPECT_EQ(Canvas::TextWidth("ab", 2), 22);
  EXPECT_EQ(Canvas::TextHeight("a\nb", 1), 16);
  c.Fill(kWhite);
  c.DrawText(0, 0, "I", kRed, 2);
  EXPECT_EQ(CountColor(c, kRed), 11 * 4);
}

TEST(CanvasTest, DownsampleAveragesAndPngRoundTrip) {
  Canvas c(4, 2, kWhite);
  c.SetPixel(0, 0, {0, 0, 0});
  c.SetPixel(1, 1, {0, 0, 0});
  const Canvas small = c.Downsampled(2);
  ASSERT_EQ(small.width(), 2);
  ASSERT_EQ(small.height(), 1);
  EXPECT_EQ(small.Pixel(0, 0), (Rgb{128, 128, 128}));
  EXPECT_EQ(small.Pixel(1, 0), kWhite);
  testing::TempDir dir;
  c.SavePng(dir.File("c.png"));
  EXPECT_EQ(ReadPngRgb(dir.File("c.png")).rgb, c.rgb());
}

}  // namespace
}  // namespace objscan::io
