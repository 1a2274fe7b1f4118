// The AWS RoboMaker small house (../shared/data/aws-small-house): every model of the world, each an
// <include> nested in a <model>, loaded with the pose and category the world and the AWS map give.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "objscan/geometry/pose.h"
#include "objscan/io/gazebo_world.h"
#include "objscan/io/scene_spec.h"
#include "objscan/io/test_util.h"
#include "shared_data.h"

namespace objscan::io {
namespace {

using testing::ByName;

world::Scene LoadHouse(const std::string& data) {
  SceneLoadOptions options;
  options.model_path = data + "/aws-small-house/models";
  return LoadScene(data + "/aws-small-house/worlds/small_house.world", options);
}

TEST(AwsSmallHouseTest, EveryModelLoadsWithItsCategory) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  const world::Scene scene = LoadHouse(data);
  // The world file holds 89 <model> blocks, two of them commented out (Ball_01_002 and the
  // RoomCeiling, "removed for easier view"): 87 models, plus the floor quad of the ground plane.
  ASSERT_EQ(scene.objects().size(), 88u);
  EXPECT_TRUE(scene.missing_meshes().empty());
  EXPECT_TRUE(scene.unmapped_models().empty()) << scene.unmapped_models().front();
  EXPECT_EQ(ByName(scene, "Ball_01_002"), nullptr);
  EXPECT_EQ(ByName(scene, "RoomCeiling_01_001"), nullptr);
  std::map<world::Category, int> count;
  for (const auto& o : scene.objects()) ++count[o.category];
  EXPECT_EQ(count[world::Category::kBed], 1);
  EXPECT_EQ(count[world::Category::kChair], 8);     // ChairA x5, ChairD x3
  EXPECT_EQ(count[world::Category::kWindow], 9);    // RoomWindow x9
  EXPECT_EQ(count[world::Category::kDoor], 5);      // Door, FoldingDoor x4
  EXPECT_EQ(count[world::Category::kWall], 2);      // RoomWall, HouseWallB
  EXPECT_EQ(count[world::Category::kFloor], 2);     // FloorB and the ground plane's quad
  EXPECT_EQ(count[world::Category::kNightStand], 2);
  EXPECT_EQ(count[world::Category::kLamp], 6);      // Chandelier x4, LightC x2
  EXPECT_EQ(count[world::Category::kRefrigerator], 1);
  EXPECT_EQ(ByName(scene, "Bed_01_001")->model_name, "aws_robomaker_residential_Bed_01");
  // The outer walls (HouseWallB) are 19 m x 11.4 m and 3 m high; they size the floor quad.
  const geometry::Aabb3 walls = scene.StructureBounds(world::Category::kWall);
  EXPECT_NEAR(walls.Size().x(), 19.0, 0.01);
  EXPECT_NEAR(walls.Size().y(), 11.4, 0.01);
  EXPECT_NEAR(walls.max_m.z(), 3.0, 0.01);
  const geometry::Aabb3 floor = scene.ObjectBounds(scene.objects()[0]);
  EXPECT_NEAR(floor.Size().x(), 19.0 + 2 * kFloorMarginM, 0.01);
}

TEST(AwsSmallHouseTest, PosesAreTheWorldFilesModelPoses) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  const world::Scene scene = LoadHouse(data);
  // <pose frame=''> of the wrapping <model>, copied from small_house.world.
  const struct {
    const char* name;
    double x, y, z, roll, pitch, yaw;
  } expected[] = {
      {"Bed_01_001", -6.165067, 2.030560, -0.000010, 0, 0, 0},
      {"NightStand_01_002", -4.407341, 2.860420, 0.005256, 0, 0.000002, 0},
      {"ChairA_01_001", 7.11516, 0.209028, 0.024685, 1e-06, -0, -1.55607},
      {"Refrigerator_01_001", 8.702731, -1.032031, 0, 0, -0, -1.563499},
      {"DeskPortraitB_01", 3.547376, -5.083898, -0.012660, -0.336622, -0.000001, 3.046741},
      {"RoomWindow_01_006", 3.488520, 5.600688, 0.502739, 0, -0, -1.566274},
  };
  for (const auto& e : expected) {
    SCOPED_TRACE(e.name);
    const world::SceneObject* o = ByName(scene, e.name);
    ASSERT_NE(o, nullptr);
    const geometry::Pose3 T = geometry::PoseFromXyzRpy(e.x, e.y, e.z, e.roll, e.pitch, e.yaw);
    EXPECT_LT((o->T_world_object.matrix() - T.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  }
  // The bed stands on the floor and is about 2 m long (centimetre COLLADA converted to metres).
  const geometry::Aabb3 bed = scene.ObjectBounds(*ByName(scene, "Bed_01_001"));
  EXPECT_NEAR(bed.min_m.z(), 0.0, 0.02);
  EXPECT_GT(std::max(bed.Size().x(), bed.Size().y()), 1.8);
  EXPECT_LT(std::max(bed.Size().x(), bed.Size().y()), 2.6);
}

// The world as shipped has its RoomCeiling commented out; with it back the house has a ceiling,
// which the AWS map makes structure.
TEST(AwsSmallHouseTest, TheRestoredCeilingIsStructure) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  std::ifstream in(data + "/aws-small-house/worlds/small_house.world");
  std::stringstream text;
  text << in.rdbuf();
  std::string world = text.str();
  const std::string opening = "<!-- Remove ceiling for easier view";
  const auto begin = world.find(opening);
  ASSERT_NE(begin, std::string::npos);
  const auto end = world.find("-->", begin);
  world = world.substr(0, begin) + world.substr(begin + opening.size(), end - begin - opening.size()) +
          world.substr(end + 3);
  testing::TempDir dir;
  testing::WriteText(dir.File("small_house_with_ceiling.world"), world);
  SceneLoadOptions options;
  options.model_path = data + "/aws-small-house/models";
  const world::Scene scene = LoadScene(dir.File("small_house_with_ceiling.world"), options);
  ASSERT_EQ(scene.objects().size(), 89u);
  const world::SceneObject* ceiling = ByName(scene, "RoomCeiling_01_001");
  ASSERT_NE(ceiling, nullptr);
  EXPECT_EQ(ceiling->category, world::Category::kCeiling);
  EXPECT_TRUE(ceiling->IsStructural());
  EXPECT_EQ(scene.NumFurniture(), LoadHouse(data).NumFurniture());
  EXPECT_NEAR(ceiling->T_world_object.translation().z(), 2.5, 1e-12);
}

}  // namespace
}  // namespace objscan::io
