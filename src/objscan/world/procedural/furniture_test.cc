#include <gtest/gtest.h>

#include <map>
#include <set>
#include <tuple>

#include "objscan/common/error.h"
#include "objscan/world/procedural/furniture_generators.h"
#include "objscan/world/procedural/procedural.h"

namespace objscan::world::procedural {
namespace {

// Realistic bounding-box sizes (depth x, width y, height z in metres) per category: [min, max].
struct SizeBounds {
  double lo[3], hi[3];
};
const std::map<Category, SizeBounds>& RealisticSizes() {
  static const std::map<Category, SizeBounds> kSizes = {
      {Category::kBathtub, {{0.65, 1.4, 0.45}, {1.3, 1.95, 2.1}}},
      {Category::kBed, {{1.9, 0.85, 0.45}, {2.4, 1.9, 1.45}}},
      {Category::kCabinet, {{0.35, 0.38, 0.7}, {0.7, 1.65, 2.2}}},
      {Category::kChair, {{0.38, 0.4, 0.7}, {0.7, 0.7, 1.25}}},
      {Category::kCurtain, {{0.05, 0.85, 1.0}, {0.25, 2.1, 2.35}}},
      {Category::kDesk, {{0.5, 0.95, 0.7}, {1.9, 1.65, 1.3}}},
      {Category::kDoor, {{0.03, 0.75, 1.95}, {0.25, 0.95, 2.15}}},
      {Category::kDresser, {{0.4, 0.8, 0.7}, {0.65, 1.7, 2.0}}},
      {Category::kLamp, {{0.1, 0.1, 0.3}, {1.7, 0.6, 2.05}}},
      {Category::kMonitor, {{0.1, 0.4, 0.3}, {0.7, 1.35, 0.95}}},
      {Category::kNightStand, {{0.3, 0.35, 0.4}, {0.6, 0.65, 0.7}}},
      {Category::kRadio, {{0.06, 0.1, 0.06}, {0.4, 0.6, 0.75}}},
      {Category::kRefrigerator, {{0.55, 0.4, 0.75}, {0.85, 0.95, 2.0}}},
      {Category::kShelves, {{0.2, 0.55, 0.75}, {0.45, 1.25, 2.05}}},
      {Category::kSink, {{0.35, 0.45, 0.8}, {0.7, 1.55, 1.3}}},
      {Category::kSofa, {{0.8, 1.0, 0.7}, {1.9, 2.6, 1.0}}},
      {Category::kTable, {{0.45, 0.55, 0.35}, {1.2, 1.95, 0.8}}},
      {Category::kToilet, {{0.45, 0.33, 0.4}, {0.85, 0.55, 2.15}}},
      {Category::kTvStand, {{0.3, 0.95, 0.35}, {0.6, 1.95, 0.65}}},
      {Category::kWindow, {{0.04, 0.55, 0.85}, {0.2, 2.25, 1.55}}},
  };
  return kSizes;
}

TEST(FurnitureTest, EveryCategoryStandsOnTheFloorCentredWithRealisticSize) {
  ASSERT_EQ(FurnitureCategories().size(), 20u);
  for (Category c : FurnitureCategories()) {
    const SizeBounds& bounds = RealisticSizes().at(c);
    for (std::uint64_t seed = 0; seed < 30; ++seed) {
      const FurnitureModel m = GenerateFurniture(c, seed);
      SCOPED_TRACE(m.name);
      ASSERT_EQ(m.category, c);
      ASSERT_FALSE(m.mesh.Empty());
      const geometry::Aabb3 box = geometry::Bounds(m.mesh);
      EXPECT_EQ(box.min_m.z(), 0.0);
      EXPECT_NEAR(box.Center().x(), 0.0, 1e-5);
      EXPECT_NEAR(box.Center().y(), 0.0, 1e-5);
      const Eigen::Vector3d size = box.Size();
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(size[k], bounds.lo[k]) << "axis " << k;
        EXPECT_LE(size[k], bounds.hi[k]) << "axis " << k;
      }
      for (const auto& t : m.mesh.triangles) {
        ASSERT_TRUE((t.array() >= 0).all() && (t.array() < static_cast<int>(m.mesh.vertices.size())).all());
      }
      geometry::TriangleMesh copy = m.mesh;
      EXPECT_EQ(geometry::RemoveDegenerateTriangles(&copy), 0u);
    }
  }
}

TEST(FurnitureTest, PartsFormOneConnectedShape) {
  for (Category c : FurnitureCategories()) {
    for (std::uint64_t seed = 0; seed < 40; ++seed) {
      PartBuilder parts;
      std::string variant;
      ASSERT_TRUE(internal::BuildFurnitureFromSeed(c, seed, &parts, &variant));
      EXPECT_EQ(parts.NumConnectedGroups(1e-4), 1) << CategoryName(c) << "_" << variant << " seed " << seed;
    }
  }
}

TEST(FurnitureTest, SameSeedSameModelAndNameEncodesVariantAndSeed) {
  for (Category c : FurnitureCategories()) {
    const FurnitureModel a = GenerateFurniture(c, 1234567);
    const FurnitureModel b = GenerateFurniture(c, 1234567);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.model_seed, 1234567u);
    ASSERT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
    for (std::size_t i = 0; i < a.mesh.vertices.size(); ++i) ASSERT_EQ(a.mesh.vertices[i], b.mesh.vertices[i]);
    ASSERT_EQ(a.mesh.triangles, b.mesh.triangles);
    const std::string prefix = std::string(CategoryName(c)) + "_";
    EXPECT_EQ(a.name.compare(0, prefix.size(), prefix), 0) << a.name;
    EXPECT_NE(a.name.find("_s1234567"), std::string::npos) << a.name;
  }
}

TEST(FurnitureTest, AtLeastSixVisiblyDifferentVariantsPerCategory) {
  for (Category c : FurnitureCategories()) {
    std::set<std::string> variants;
    for (std::uint64_t seed = 0; seed < 60; ++seed) {
      const FurnitureModel m = GenerateFurniture(c, seed);
      variants.insert(m.name.substr(0, m.name.rfind("_s")));
    }
    EXPECT_GE(variants.size(), 6u) << CategoryName(c);
    // Twelve seeds give at least six different shapes (size rounded to 5 cm, triangle count).
    std::set<std::tuple<int, int, int, std::size_t>> shapes;
    for (std::uint64_t seed = 100; seed < 112; ++seed) {
      const FurnitureModel m = GenerateFurniture(c, seed);
      const Eigen::Vector3d size = geometry::Bounds(m.mesh).Size() / 0.05;
      shapes.insert({static_cast<int>(size.x()), static_cast<int>(size.y()), static_cast<int>(size.z()),
                     m.mesh.NumTriangles()});
    }
    EXPECT_GE(shapes.size(), 6u) << CategoryName(c);
  }
}

TEST(FurnitureTest, VariantsOfOneCategoryDifferInShape) {
  // Different variant names must not share both triangle count and rounded size.
  for (Category c : FurnitureCategories()) {
    std::map<std::string, std::set<std::size_t>> triangles_by_variant;
    for (std::uint64_t seed = 0; seed < 60; ++seed) {
      const FurnitureModel m = GenerateFurniture(c, seed);
      triangles_by_variant[m.name.substr(0, m.name.rfind("_s"))].insert(m.mesh.NumTriangles());
    }
    std::set<std::size_t> counts;
    for (const auto& [variant, tris] : triangles_by_variant) counts.insert(tris.begin(), tris.end());
    EXPECT_GE(counts.size(), 4u) << CategoryName(c);
  }
}

TEST(FurnitureTest, CategoriesWithoutGeneratorThrow) {
  for (Category c : {Category::kCan, Category::kOther, Category::kFloor, Category::kWall}) {
    EXPECT_THROW(GenerateFurniture(c, 1), InputError);
  }
}

TEST(FurnitureTest, DatabaseSeedsNeverCollideWithSceneSeeds) {
  std::set<std::uint64_t> scene_seeds;
  for (const auto& room : RoomCategories()) {
    for (std::uint64_t s = 0; s < 20; ++s) {
      for (std::uint64_t k = 0; k < 50; ++k) {
        const std::uint64_t seed = SceneModelSeed(room, s, k);
        EXPECT_EQ(seed & kDatabaseSeedBit, 0u);
        scene_seeds.insert(seed);
      }
    }
  }
  EXPECT_EQ(scene_seeds.size(), 5u * 20u * 50u);
  std::set<std::uint64_t> db_seeds;
  for (std::uint64_t i = 0; i < 5000; ++i) {
    const std::uint64_t seed = DatabaseModelSeed(i);
    EXPECT_NE(seed & kDatabaseSeedBit, 0u);
    EXPECT_EQ(scene_seeds.count(seed), 0u);
    db_seeds.insert(seed);
  }
  EXPECT_EQ(db_seeds.size(), 5000u);
}

}  // namespace
}  // namespace objscan::world::procedural
