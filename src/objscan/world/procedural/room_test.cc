#include <gtest/gtest.h>

#include <cmath>

#include "objscan/common/error.h"
#include "objscan/world/procedural/floor_check.h"
#include "objscan/world/procedural/procedural.h"
#include "objscan/world/procedural/room_builder.h"
#include "objscan/world/procedural/surface_probe.h"

namespace objscan::world::procedural {
namespace {

constexpr std::uint64_t kSeeds[] = {1, 2, 3, 7, 42, 1000};

bool SameScene(const Scene& a, const Scene& b) {
  if (a.objects().size() != b.objects().size()) return false;
  for (std::size_t i = 0; i < a.objects().size(); ++i) {
    const SceneObject& x = a.objects()[i];
    const SceneObject& y = b.objects()[i];
    if (x.instance_id != y.instance_id || x.category != y.category || x.name != y.name ||
        x.model_name != y.model_name || !(x.T_world_object.matrix().array() == y.T_world_object.matrix().array()).all() ||
        x.mesh.vertices != y.mesh.vertices || x.mesh.triangles != y.mesh.triangles) {
      return false;
    }
  }
  return true;
}

bool OnFloor(const Scene& scene, double x, double y) {
  for (const auto& o : scene.objects()) {
    if (o.category != Category::kFloor) continue;
    double z = 0.0;
    if (SurfaceProbe(o).TopHeightAt(x, y, &z)) return true;
  }
  return false;
}

// Distance between two boxes' XY footprints (0 when they overlap).
double FootprintDistance(const geometry::Aabb3& a, const geometry::Aabb3& b) {
  const double dx = std::max({0.0, a.min_m.x() - b.max_m.x(), b.min_m.x() - a.max_m.x()});
  const double dy = std::max({0.0, a.min_m.y() - b.max_m.y(), b.min_m.y() - a.max_m.y()});
  return std::hypot(dx, dy);
}

bool WallMounted(const SceneObject& o, const geometry::Aabb3& box) {
  return o.category == Category::kWindow || (o.category == Category::kCurtain && box.min_m.z() > 0.05);
}

class RoomTest : public ::testing::TestWithParam<std::string> {};

TEST_P(RoomTest, SameSeedSameSceneAndOtherSeedsDiffer) {
  for (std::uint64_t seed : kSeeds) {
    const Scene a = GenerateRoom(GetParam(), seed);
    const Scene b = GenerateRoom(GetParam(), seed);
    EXPECT_TRUE(SameScene(a, b)) << GetParam() << " seed " << seed;
    EXPECT_EQ(a.name(), "procedural:" + GetParam() + ":" + std::to_string(seed));
    const Scene c = GenerateRoom(GetParam(), seed + 1);
    EXPECT_FALSE(SameScene(a, c)) << GetParam() << " seed " << seed;
  }
}

TEST_P(RoomTest, StructureAndObjectCount) {
  for (std::uint64_t seed : kSeeds) {
    SCOPED_TRACE(GetParam() + ":" + std::to_string(seed));
    const Scene scene = GenerateRoom(GetParam(), seed);
    EXPECT_GE(scene.NumFurniture(), 6u);
    EXPECT_LE(scene.NumFurniture(), 20u);
    int floors = 0, walls = 0, doors = 0;
    for (std::size_t i = 0; i < scene.objects().size(); ++i) {
      const SceneObject& o = scene.objects()[i];
      EXPECT_EQ(o.instance_id, static_cast<std::int32_t>(i + 1));
      EXPECT_EQ(o.name, std::string(CategoryName(o.category)) + "_" + std::to_string(o.instance_id));
      const geometry::Aabb3 box = scene.ObjectBounds(o);
      if (o.category == Category::kFloor) {
        ++floors;
        EXPECT_EQ(box.min_m.z(), 0.0);
        EXPECT_EQ(box.max_m.z(), 0.0);
      } else if (o.category == Category::kWall) {
        ++walls;
        EXPECT_EQ(box.min_m.z(), 0.0);
        EXPECT_GE(box.max_m.z(), 2.4);
        EXPECT_LE(box.max_m.z(), 3.0);
        EXPECT_NEAR(std::min(box.Size().x(), box.Size().y()), 0.1, 1e-6);
      } else {
        doors += o.category == Category::kDoor;
        // Furniture is procedural, regenerates from its model name, and its seed is a scene seed.
        Category c;
        std::uint64_t model_seed = 0;
        ASSERT_TRUE(ParseProceduralModelName(o.model_name, &c, &model_seed)) << o.model_name;
        EXPECT_EQ(c, o.category);
        EXPECT_EQ(model_seed & kDatabaseSeedBit, 0u);
        EXPECT_EQ(GenerateFurniture(c, model_seed).mesh.vertices, o.mesh.vertices);
      }
    }
    EXPECT_EQ(floors, 1);
    EXPECT_TRUE(walls == 4 || walls == 6) << walls;
    EXPECT_EQ(doors, 1);
  }
}

TEST_P(RoomTest, FreeFloorIsConnectedWithWidePassagesAndEverythingReachable) {
  for (std::uint64_t seed : kSeeds) {
    const Scene scene = GenerateRoom(GetParam(), seed);
    const FloorConnectivityReport r = CheckFreeFloor(scene, 0.05, 0.8, 1.5);
    EXPECT_TRUE(r.ok) << GetParam() << ":" << seed << " components " << r.num_components << " unreachable "
                      << r.unreachable_instances.size();
    EXPECT_EQ(r.num_components, 1);
    EXPECT_GT(r.eroded_free_cells, 100u);
  }
}

TEST_P(RoomTest, NoOverlapsEverythingInsideOnTopObjectsRest) {
  for (std::uint64_t seed : kSeeds) {
    SCOPED_TRACE(GetParam() + ":" + std::to_string(seed));
    const Scene scene = GenerateRoom(GetParam(), seed);
    const geometry::Aabb3 walls = scene.StructureBounds(Category::kWall);
    std::vector<const SceneObject*> standing, on_top;
    for (const auto& o : scene.objects()) {
      if (o.IsStructural()) continue;
      const geometry::Aabb3 box = scene.ObjectBounds(o);
      EXPECT_GE(box.min_m.z(), 0.0) << o.name;
      if (WallMounted(o, box)) {
        // In (or against) the wall band: inside the walls' extent and near a wall.
        EXPECT_TRUE(walls.Contains(box.min_m, 1e-6) && walls.Contains(box.max_m, 1e-6)) << o.name;
        double nearest = 1e9;
        for (const auto& w : scene.objects()) {
          if (w.category == Category::kWall) nearest = std::min(nearest, FootprintDistance(box, scene.ObjectBounds(w)));
        }
        EXPECT_LE(nearest, 0.25) << o.name;
        continue;
      }
      (box.min_m.z() < 0.05 ? standing : on_top).push_back(&o);
    }
    for (const SceneObject* o : standing) {
      const geometry::Aabb3 box = scene.ObjectBounds(*o);
      const double e = 1e-3;
      for (double x : {box.min_m.x() + e, box.max_m.x() - e}) {
        for (double y : {box.min_m.y() + e, box.max_m.y() - e}) EXPECT_TRUE(OnFloor(scene, x, y)) << o->name;
      }
      for (const SceneObject* p : standing) {
        if (p != o) {
          EXPECT_FALSE(box.FootprintOverlaps(scene.ObjectBounds(*p))) << o->name << " / " << p->name;
        }
      }
    }
    for (const SceneObject* o : on_top) {
      const geometry::Aabb3 box = scene.ObjectBounds(*o);
      const Eigen::Vector3d c = box.Center();
      bool rests = false;
      for (const SceneObject* s : standing) {
        double z = 0.0;
        rests = rests || (SurfaceProbe(*s).TopHeightAt(c.x(), c.y(), &z) && std::abs(z - box.min_m.z()) < 1e-4);
      }
      EXPECT_TRUE(rests) << o->name << " floats at z = " << box.min_m.z();
    }
  }
}

TEST_P(RoomTest, KeyFurnitureOfTheCategory) {
  // Each room has at least one object of each listed group (any category of the group).
  const std::map<std::string, std::vector<std::vector<Category>>> key = {
      {"bedroom", {{Category::kBed}, {Category::kDoor}}},
      {"living_room", {{Category::kSofa}}},
      {"kitchen", {{Category::kCabinet, Category::kSink}}},
      {"bathroom", {{Category::kToilet}}},
      {"office", {{Category::kDesk}}}};
  for (std::uint64_t seed : kSeeds) {
    const Scene scene = GenerateRoom(GetParam(), seed);
    for (const auto& group : key.at(GetParam())) {
      bool found = false;
      for (const auto& o : scene.objects()) {
        for (Category c : group) found = found || o.category == c;
      }
      EXPECT_TRUE(found) << GetParam() << ":" << seed << " lacks " << CategoryName(group.front());
    }
  }
}

TEST(RoomGeneratorTest, RoomsAreRectangularOrLShaped) {
  int rectangles = 0, l_shapes = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const Scene scene = GenerateRoom("office", seed);
    int walls = 0;
    for (const auto& o : scene.objects()) walls += o.category == Category::kWall;
    (walls == 4 ? rectangles : l_shapes) += 1;
  }
  EXPECT_GT(rectangles, 0);
  EXPECT_GT(l_shapes, 0);
}

INSTANTIATE_TEST_SUITE_P(AllCategories, RoomTest,
                         ::testing::Values("bedroom", "living_room", "kitchen", "bathroom", "office"));

TEST(RoomGeneratorTest, UnknownCategoryThrows) {
  EXPECT_THROW(GenerateRoom("garage", 1), InputError);
  EXPECT_EQ(RoomCategories().size(), 5u);
}

TEST(RoomGeneratorTest, ModelNamesRoundTrip) {
  Category c;
  std::uint64_t seed = 0;
  ASSERT_TRUE(ParseProceduralModelName(ProceduralModelName(Category::kNightStand, 987654321), &c, &seed));
  EXPECT_EQ(c, Category::kNightStand);
  EXPECT_EQ(seed, 987654321u);
  EXPECT_FALSE(ParseProceduralModelName("procedural/spaceship/1", &c, &seed));
  EXPECT_FALSE(ParseProceduralModelName("403", &c, &seed));
}

}  // namespace
}  // namespace objscan::world::procedural
