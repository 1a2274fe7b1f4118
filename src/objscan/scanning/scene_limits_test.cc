#include "objscan/scanning/scene_limits.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"
#include "objscan/geometry/mesh.h"

namespace objscan::scanning {
namespace {

// A room of `side_m` x `side_m` (2.5 m high walls as one box each) with a 12-triangle table.
world::Scene Room(double side_m) {
  world::Scene scene("room");
  auto add = [&](world::Category category, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    world::SceneObject o;
    o.category = category;
    o.name = world::CategoryName(category);
    o.mesh = geometry::MakeBox(lo, hi);
    scene.Add(std::move(o));
  };
  add(world::Category::kFloor, {0, 0, -0.01}, {side_m, side_m, 0});
  add(world::Category::kWall, {0, 0, 0}, {side_m, 0.1, 2.5});
  add(world::Category::kTable, {1, 1, 0}, {1.8, 1.6, 0.75});
  return scene;
}

// The InputError message of CheckSceneLimits ("" when the scene fits).
std::string Failure(const world::Scene& scene, const SystemConfig& config) {
  try {
    CheckSceneLimits(scene, config, "room.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneLimitsTest, ARoomWithinTheDefaultsPasses) {
  EXPECT_EQ(Failure(Room(8.0), SystemConfig{}), "");
  // The largest side at the limit passes.
  SystemConfig config;
  config.scene.max_extent_m = 8.0;
  EXPECT_EQ(Failure(Room(8.0), config), "");
}

TEST(SceneLimitsTest, TooWideASceneNamesTheExtentAndItsKey) {
  const std::string message = Failure(Room(150.0), SystemConfig{});
  EXPECT_NE(message.find("room.yaml: the scene spans 150 x 150 x 2.51 m"), std::string::npos) << message;
  EXPECT_NE(message.find("scene.max_extent_m = 100 m"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  SystemConfig config;
  config.scene.max_extent_m = 200.0;
  EXPECT_EQ(Failure(Room(150.0), config), "");
}

TEST(SceneLimitsTest, TooManyTrianglesNamesTheCountAndItsKey) {
  SystemConfig config;
  config.scene.max_triangles = 35;  // the room has 3 boxes of 12 triangles
  const std::string message = Failure(Room(8.0), config);
  EXPECT_NE(message.find("the scene has 36 triangles, more than scene.max_triangles = 35"), std::string::npos) << message;
  config.scene.max_triangles = 36;
  EXPECT_EQ(Failure(Room(8.0), config), "");
}

TEST(SceneLimitsTest, AGridTooFineForTheSceneNamesItsResolutionKey) {
  // 90 m at 1 cm: 9000 x 9000 = 8.1e7 navigation cells, past the 6.4e7 a 2D grid may have.
  SystemConfig config;
  config.navigation.cell_size_m = 0.01;
  std::string message = Failure(Room(90.0), config);
  EXPECT_NE(message.find("needs a navigation grid of 8.1e+07 cells at navigation.cell_size_m = 0.01 m"),
            std::string::npos)
      << message;
  // The evaluation's voxels: 90 m x 90 m x 2.5 m at 1 cm is 2e10 cells.
  config = SystemConfig{};
  config.eval.coverage_voxel_size_m = 0.01;
  message = Failure(Room(90.0), config);
  EXPECT_NE(message.find("eval.coverage_voxel_size_m = 0.01 m"), std::string::npos) << message;
  // The occupancy snapshot counts only when something uses it (recognition.space_weight > 0).
  config = SystemConfig{};
  config.occupancy.resolution_m = 0.01;
  EXPECT_EQ(Failure(Room(90.0), config), "");
  config.recognition.space_weight = 1.0;
  message = Failure(Room(90.0), config);
  EXPECT_NE(message.find("occupancy.resolution_m = 0.01 m"), std::string::npos) << message;
}

}  // namespace
}  // namespace objscan::scanning
