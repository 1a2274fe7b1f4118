#include "objscan/io/topview.h"

#include <gtest/gtest.h>

namespace objscan::io {
namespace {

Rgb ColorOf(world::Category c) {
  const auto rgb = world::CategoryColor(c);
  return {rgb[0], rgb[1], rgb[2]};
}

// Hue test that tolerates the height shading: the pixel is a scaled/lightened version of `c` when
// its channel order matches.
bool LooksLike(const Rgb& pixel, const Rgb& c) {
  const auto distance = [](const Rgb& a, const Rgb& b) {
    return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
  };
  for (double f = 0.5; f <= 1.4; f += 0.02) {
    for (double t = 0; t <= 0.5; t += 0.05) {
      if (distance(pixel, ShadeRgb(MixRgb(c, {255, 255, 255}, t), f)) < 12) return true;
    }
  }
  return false;
}

world::SceneObject Box(world::Category c, const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m) {
  world::SceneObject o;
  o.category = c;
  o.mesh = geometry::MakeBox(min_m, max_m);
  return o;
}

TEST(TopViewTest, HigherSurfacesCoverLowerOnesAndColoursFollowCategories) {
  world::Scene scene("test");
  world::SceneObject floor;
  floor.category = world::Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(-1, -1, 3, 3);
  scene.Add(floor);
  scene.Add(Box(world::Category::kWall, {-1, -1, 0}, {3, -0.9, 2.5}));
  scene.Add(Box(world::Category::kTable, {0, 0, 0}, {1, 1, 0.75}));
  // A lamp on the table (higher) and a bed beside it; the lamp comes before the table in the object
  // list, so only the height buffer can put it on top.
  scene.Add(Box(world::Category::kBed, {1.5, 0, 0}, {2.5, 2, 0.5}));
  world::SceneObject lamp = Box(world::Category::kLamp, {0.4, 0.4, 0.75}, {0.6, 0.6, 1.2});
  scene.mutable_objects().insert(scene.mutable_objects().begin() + 1, lamp);
  scene.mutable_objects()[1].instance_id = 99;

  TopViewOptions options;
  options.metres_per_pixel = 0.02;
  const TopView view = RenderTopView(scene, options);
  const auto at = [&](double x, double y) {
    const Eigen::Vector2d p = view.map.ToPixel(x, y);
    return view.canvas.Pixel(static_cast<int>(p.x()), static_cast<int>(p.y()));
  };
  EXPECT_TRUE(LooksLike(at(0.5, 0.5), ColorOf(world::Category::kLamp)));
  EXPECT_TRUE(LooksLike(at(0.2, 0.8), ColorOf(world::Category::kTable)));
  EXPECT_TRUE(LooksLike(at(2.0, 1.0), ColorOf(world::Category::kBed)));
  EXPECT_EQ(at(1.25, 2.0), ColorOf(world::Category::kFloor));
  EXPECT_EQ(at(1.0, -0.95), ColorOf(world::Category::kWall));
  // The legend to the right of the map holds a swatch of each category present.
  int swatches = 0;
  for (world::Category c : {world::Category::kTable, world::Category::kLamp, world::Category::kBed,
                            world::Category::kWall, world::Category::kFloor}) {
    bool found = false;
    for (int y = 0; y < view.canvas.height() && !found; ++y) {
      for (int x = view.map.width_px(); x < view.canvas.width() && !found; ++x) {
        found = view.canvas.Pixel(x, y) == ColorOf(c);
      }
    }
    swatches += found;
  }
  EXPECT_EQ(swatches, 5);
  EXPECT_GT(view.canvas.width(), view.map.width_px());
}

TEST(TopViewTest, RejectsHugeImages) {
  world::Scene scene("big");
  scene.Add(Box(world::Category::kTable, {0, 0, 0}, {500, 1, 1}));
  TopViewOptions options;
  options.metres_per_pixel = 0.01;
  EXPECT_THROW(RenderTopView(scene, options), InputError);
  options.metres_per_pixel = 0.0;
  EXPECT_THROW(RenderTopView(scene, options), ConfigError);
}

// A scanned wall is a surface of vertical triangles, without the thickness of a panel: drawn from
// its edges, not left out; a ceiling is not drawn (it would hide the room).
TEST(TopViewTest, ZeroThicknessWallsAreDrawnAndCeilingsAreNot) {
  world::Scene scene("test");
  world::SceneObject floor;
  floor.category = world::Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(0, 0, 3, 3);
  scene.Add(floor);
  world::SceneObject wall;
  wall.category = world::Category::kWall;
  wall.mesh.vertices = {{0, 1.5f, 0}, {3, 1.5f, 0}, {3, 1.5f, 2.4f}, {0, 1.5f, 2.4f}};
  wall.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.Add(wall);
  world::SceneObject ceiling;
  ceiling.category = world::Category::kCeiling;
  ceiling.mesh = geometry::MakeQuadXY(0, 0, 3, 3);
  for (auto& v : ceiling.mesh.vertices) v.z() = 2.4f;
  scene.Add(ceiling);
  TopViewOptions options;
  options.metres_per_pixel = 0.02;
  const TopView view = RenderTopView(scene, options);
  const auto at = [&](double x, double y) {
    const Eigen::Vector2d p = view.map.ToPixel(x, y);
    return view.canvas.Pixel(static_cast<int>(p.x()), static_cast<int>(p.y()));
  };
  EXPECT_EQ(at(1.5, 1.5), ColorOf(world::Category::kWall));
  // The map spans the wall plus the margin (0.3 m); the floor either side is seen through the ceiling.
  EXPECT_EQ(at(1.5, 1.3), ColorOf(world::Category::kFloor));
  EXPECT_EQ(at(1.5, 1.7), ColorOf(world::Category::kFloor));
}

}  // namespace
}  // namespace objscan::io
