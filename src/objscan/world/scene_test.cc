#include "objscan/world/scene.h"

#include <gtest/gtest.h>

namespace objscan::world {
namespace {

TEST(CategoryTest, NamesRoundTrip) {
  for (int i = 0; i < kNumCategories; ++i) {
    const auto c = static_cast<Category>(i);
    ASSERT_EQ(ParseCategory(CategoryName(c)), c);
  }
  EXPECT_FALSE(ParseCategory("spaceship").has_value());
  EXPECT_TRUE(IsStructural(Category::kWall));
  EXPECT_FALSE(IsStructural(Category::kChair));
}

// PLY labels: a category's own colour, the unrecognized grey for -1 and ids out of range.
TEST(CategoryTest, LabelColors) {
  EXPECT_EQ(LabelColor(CategoryId(Category::kSofa)), CategoryColor(Category::kSofa));
  EXPECT_EQ(LabelColor(CategoryId(Category::kCeiling)), CategoryColor(Category::kCeiling));
  EXPECT_EQ(LabelColor(-1), (std::array<unsigned char, 3>{165, 165, 165}));
  EXPECT_EQ(LabelColor(kNumCategories), kUnrecognizedColor);
  EXPECT_NE(LabelColor(-1), CategoryColor(Category::kOther));
}

TEST(SceneTest, SoupCarriesInstanceIdsAndWorldCoordinates) {
  Scene scene("t");
  SceneObject box;
  box.category = Category::kTable;
  box.mesh = geometry::MakeBox(Eigen::Vector3d(1, 1, 1));
  box.T_world_object.translation() = Eigen::Vector3d(5, 0, 0.5);
  const auto id = scene.Add(box);
  SceneObject floor;
  floor.category = Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(-10, -10, 10, 10);
  const auto floor_id = scene.Add(floor);
  EXPECT_NE(id, floor_id);
  EXPECT_EQ(scene.NumFurniture(), 1u);
  const TriangleSoup soup = scene.BuildTriangleSoup();
  ASSERT_EQ(soup.NumTriangles(), 14u);
  EXPECT_EQ(soup.triangle_instance.front(), id);
  EXPECT_EQ(soup.triangle_instance.back(), floor_id);
  EXPECT_FLOAT_EQ(soup.vertices_xyz[0], 4.5f);
  const auto b = scene.FurnitureBounds();
  EXPECT_NEAR(b.min_m.z(), 0.0, 1e-9);
  EXPECT_NEAR(b.max_m.x(), 5.5, 1e-9);
  SceneObject dup = box;
  dup.instance_id = id;
  EXPECT_THROW(scene.Add(dup), std::invalid_argument);
}

}  // namespace
}  // namespace objscan::world
