#include "objscan/eval/exposure.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"
#include "objscan/geometry/mesh.h"
#include "objscan/sim/test_scenes.h"

namespace objscan::eval {
namespace {

using sim::testing::BoxObject;
using sim::testing::Room;

constexpr double kVoxel_m = 0.1;

Eigen::Vector3d Center(int x, int y, int z) { return (Eigen::Vector3d(x, y, z) + Eigen::Vector3d::Constant(0.5)) * kVoxel_m; }

// A closed 0.6 m box on the floor of a 3 x 3 m room, faces mid-voxel (x, y in [1.05, 1.65],
// z in [0.05, 0.65]; the floor's layer is z in [0, 0.1]).
world::Scene RoomWithBox() {
  world::Scene scene = Room(3.0, 3.0);
  scene.Add(BoxObject({1.05, 1.05, 0.05}, {1.65, 1.65, 0.65}));
  return scene;
}

TEST(ExposedVoxels, OuterFacesOfABoxOnTheFloorAreExposedItsUndersideAndInsideAreNot) {
  const world::Scene scene = RoomWithBox();
  const Eigen::Vector3d seed(0.5, 0.5, 1.2);
  // Top face (layer 6), a side face (x layer 10, mid height), underside middle (layer 0), an
  // inside voxel next to no face.
  const std::vector<Eigen::Vector3d> probes = {Center(13, 13, 6), Center(10, 13, 3), Center(13, 13, 0),
                                               Center(13, 13, 3)};
  const std::vector<char> exposed = ExposedVoxels(scene, probes, kVoxel_m, seed);
  ASSERT_EQ(exposed.size(), probes.size());
  EXPECT_EQ(exposed[0], 1);
  EXPECT_EQ(exposed[1], 1);
  EXPECT_EQ(exposed[2], 0);
  EXPECT_EQ(exposed[3], 0);
}

TEST(ExposedVoxels, AnUndersideStaysHiddenWhenAirReachesUnderTheFloorThroughADoorway) {
  // The room of RoomWithBox with a 1 m doorway in its y = 3 wall (two wall pieces either side): the
  // doorway joins the room's air to the outside, which runs under the floor.
  world::Scene scene("open room");
  scene.Add(sim::testing::FloorObject(-0.1, -0.1, 3.1, 3.1));
  scene.Add(BoxObject({-0.1, -0.1, 0}, {3.1, 0, 2.5}, world::Category::kWall));
  scene.Add(BoxObject({-0.1, 0, 0}, {0, 3.0, 2.5}, world::Category::kWall));
  scene.Add(BoxObject({3.0, 0, 0}, {3.1, 3.0, 2.5}, world::Category::kWall));
  scene.Add(BoxObject({-0.1, 3.0, 0}, {1.0, 3.1, 2.5}, world::Category::kWall));
  scene.Add(BoxObject({2.0, 3.0, 0}, {3.1, 3.1, 2.5}, world::Category::kWall));
  scene.Add(BoxObject({1.05, 1.05, 0.05}, {1.65, 1.65, 0.65}));
  const std::vector<char> exposed =
      ExposedVoxels(scene, {Center(13, 13, 0), Center(13, 13, 6)}, kVoxel_m, Eigen::Vector3d(0.5, 0.5, 1.2));
  EXPECT_EQ(exposed[0], 0);
  EXPECT_EQ(exposed[1], 1);
}

TEST(ExposedVoxels, ABackFlushAgainstAWallIsNotExposedAGapWideEnoughIs) {
  world::Scene scene = Room(3.0, 3.0);
  // Flush: the back face at x = 0.02, in the wall's voxel layer next to the wall (x in [-0.1, 0]).
  scene.Add(BoxObject({0.02, 1.05, 0.05}, {0.45, 1.65, 1.05}));
  // 0.3 m off the opposite wall (x = 3): its back face at x = 2.65 faces a 0.35 m air gap.
  scene.Add(BoxObject({2.15, 1.05, 0.05}, {2.65, 1.65, 1.05}));
  const std::vector<Eigen::Vector3d> probes = {Center(0, 13, 5), Center(26, 13, 5)};
  const std::vector<char> exposed = ExposedVoxels(scene, probes, kVoxel_m, Eigen::Vector3d(1.5, 0.5, 1.2));
  EXPECT_EQ(exposed[0], 0);
  EXPECT_EQ(exposed[1], 1);
}

TEST(ExposedVoxels, ASeedInsideAClosedBoxSeesOnlyItsInside) {
  const world::Scene scene = RoomWithBox();
  const std::vector<Eigen::Vector3d> probes = {Center(13, 13, 6), Center(13, 13, 0)};
  // From inside the box the inner sides of the top and bottom faces are the exposed ones.
  const std::vector<char> exposed = ExposedVoxels(scene, probes, kVoxel_m, Eigen::Vector3d(1.35, 1.35, 0.35));
  EXPECT_EQ(exposed[0], 1);
  EXPECT_EQ(exposed[1], 1);
}

TEST(ExposedVoxels, NoVoxelIsExposedFromASeedBuriedInGeometry) {
  world::Scene scene("solid");
  // A solid block of nested shells, every voxel within two of the seed touched by a triangle.
  for (int i = 0; i < 8; ++i) {
    const double r = 0.05 + 0.05 * i;
    scene.Add(BoxObject(Eigen::Vector3d::Constant(1.0 - r), Eigen::Vector3d::Constant(1.0 + r)));
  }
  const std::vector<char> exposed =
      ExposedVoxels(scene, {Center(14, 10, 10)}, kVoxel_m, Eigen::Vector3d::Constant(1.0));
  EXPECT_EQ(exposed[0], 0);
}

TEST(ExposedVoxels, UndersidesBelowAndTopsAboveTheCameraHeightBandAreHidden) {
  world::Scene scene = Room(3.0, 3.0);
  // A slab with 25 cm of air under it (its underside in voxel layer 2, z in [0.2, 0.3]) and a
  // 2.05 m tall box (its top in layer 20, z in [2.0, 2.1]).
  scene.Add(BoxObject({1.05, 1.05, 0.25}, {1.65, 1.65, 0.55}));
  scene.Add(BoxObject({2.05, 2.05, 0.05}, {2.65, 2.65, 2.05}));
  const std::vector<Eigen::Vector3d> probes = {Center(13, 13, 2), Center(23, 23, 20), Center(20, 23, 10)};
  const Eigen::Vector3d seed(0.5, 0.5, 1.2);
  // Any camera height: all three are exposed.
  EXPECT_EQ(ExposedVoxels(scene, probes, kVoxel_m, seed), (std::vector<char>{1, 1, 1}));
  // Cameras from 0.5 to 1.8 m: the underside needs a camera below 0.3 m, the top one above 2.0 m.
  EXPECT_EQ(ExposedVoxels(scene, probes, kVoxel_m, seed, {0.5, 1.8}), (std::vector<char>{0, 0, 1}));
  // Cameras from 0.2 to 2.2 m see both.
  EXPECT_EQ(ExposedVoxels(scene, probes, kVoxel_m, seed, {0.2, 2.2}), (std::vector<char>{1, 1, 1}));
}

TEST(ExposedVoxels, RejectsANonPositiveVoxelSizeAndAnEmptyBand) {
  EXPECT_THROW(ExposedVoxels(RoomWithBox(), {}, 0.0, Eigen::Vector3d::Zero()), InputError);
  EXPECT_THROW(ExposedVoxels(RoomWithBox(), {}, 0.1, Eigen::Vector3d::Zero(), {1.0, 0.5}), InputError);
}

TEST(RoomAir, TheRobotsReachLimitsWhereTheCameraCanBe) {
  // A 1 m high platform over x in [0, 2] leaves a 1 m strip of floor: base centres (radius 0.25)
  // stand at x in [2.25, 2.75], so a camera reaching 0.6 m gets as far as x = 1.65.
  world::Scene scene = Room(3.0, 3.0);
  scene.Add(BoxObject({0.0, 0.0, 0.0}, {2.0, 3.0, 1.0}));
  RoomAir air(scene, 0.05, Eigen::Vector3d(2.5, 1.5, 1.0));
  const Eigen::Vector3d over_platform(1.4, 1.5, 1.5), near_edge(1.725, 1.5, 1.5), inside(1.0, 1.5, 0.5);
  EXPECT_TRUE(air.CameraCanBeAt(over_platform));
  EXPECT_FALSE(air.CameraCanBeAt(inside));
  air.RestrictToRobotReach(0.25, 1.8, 0.6);
  EXPECT_FALSE(air.CameraCanBeAt(over_platform));
  EXPECT_TRUE(air.CameraCanBeAt(near_edge));
  EXPECT_TRUE(air.Contains(over_platform));
  // A robot too wide for the strip would stand nowhere, yet it stands at the start: no limit then.
  RoomAir wide(scene, 0.05, Eigen::Vector3d(2.5, 1.5, 1.0));
  wide.RestrictToRobotReach(0.6, 1.8, 0.6);
  EXPECT_TRUE(wide.CameraCanBeAt(over_platform));
  EXPECT_THROW(wide.RestrictToRobotReach(-1.0, 1.8, 0.6), InputError);
}

TEST(RoomAir, ARobotStartingUnderAShelfStillReachesTheRoom) {
  // A board at 1.5 m over the start: its column is not free up to the robot's height, the floor
  // around it is.
  world::Scene scene = Room(3.0, 3.0);
  scene.Add(BoxObject({1.3, 1.3, 1.5}, {1.7, 1.7, 1.52}));
  scene.Add(BoxObject({0.0, 0.0, 0.0}, {0.5, 3.0, 2.2}));  // a tall wardrobe along x = 0
  RoomAir air(scene, 0.05, Eigen::Vector3d(1.5, 1.5, 1.0));
  air.RestrictToRobotReach(0.25, 1.8, 0.6);
  EXPECT_TRUE(air.CameraCanBeAt(Eigen::Vector3d(2.5, 2.5, 1.0)));
  EXPECT_TRUE(air.CameraCanBeAt(Eigen::Vector3d(1.5, 1.5, 1.2)));
  // Base centres stand clear of the wardrobe's front (x >= 0.8), so a camera above the wardrobe
  // reaches x = 0.2 and no further towards the wall.
  EXPECT_TRUE(air.CameraCanBeAt(Eigen::Vector3d(0.3, 1.5, 2.3)));
  EXPECT_FALSE(air.CameraCanBeAt(Eigen::Vector3d(0.1, 1.5, 2.3)));
}

}  // namespace
}  // namespace objscan::eval
