#include "objscan/world/procedural/floor_check.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"

namespace objscan::world::procedural {
namespace {

using Eigen::Vector3d;

Scene FloorOnly(double w, double d) {
  Scene scene("hand-made");
  SceneObject floor;
  floor.category = Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(0, 0, w, d);
  scene.Add(floor);
  return scene;
}

std::int32_t AddBox(Scene* scene, Category c, const Vector3d& lo, const Vector3d& hi) {
  SceneObject o;
  o.category = c;
  o.mesh = geometry::MakeBox(lo, hi);
  return scene->Add(o);
}

// A 4 x 3 m room split at x = 2 by a partition that leaves a gap of `gap_m` at the top.
Scene PartitionedRoom(double gap_m) {
  Scene scene = FloorOnly(4.0, 3.0);
  AddBox(&scene, Category::kWall, Vector3d(1.9, 0.0, 0.0), Vector3d(2.1, 3.0 - gap_m, 2.5));
  AddBox(&scene, Category::kChair, Vector3d(0.5, 0.5, 0.0), Vector3d(0.9, 0.9, 0.8));
  AddBox(&scene, Category::kChair, Vector3d(3.1, 0.5, 0.0), Vector3d(3.5, 0.9, 0.8));
  return scene;
}

TEST(FloorCheckTest, EmptySquareErodesByHalfThePassage) {
  const FloorConnectivityReport r = CheckFreeFloor(FloorOnly(2.0, 2.0), 0.05, 0.8, 1.5);
  EXPECT_EQ(r.floor_cells, 1600u);
  EXPECT_EQ(r.free_cells, 1600u);
  // Cell centres at least 0.4 m from the centres of the off-floor border cells (at -0.025 and
  // 2.025): 0.375 .. 1.625, 26 per axis.
  EXPECT_EQ(r.eroded_free_cells, 26u * 26u);
  EXPECT_EQ(r.num_components, 1);
  EXPECT_TRUE(r.ok);
}

TEST(FloorCheckTest, RejectsANarrowPassageAndAcceptsAWideOne) {
  const FloorConnectivityReport narrow = CheckFreeFloor(PartitionedRoom(0.5), 0.05, 0.8, 1.5);
  EXPECT_EQ(narrow.num_components, 2);
  EXPECT_FALSE(narrow.ok);
  const FloorConnectivityReport wide = CheckFreeFloor(PartitionedRoom(1.0), 0.05, 0.8, 1.5);
  EXPECT_EQ(wide.num_components, 1);
  EXPECT_TRUE(wide.ok);
}

TEST(FloorCheckTest, PassageThresholdIsThePassageWidth) {
  // Two blocks leaving a corridor across the room between y = 1.0 and y = 1.0 + gap.
  auto corridor = [](double gap) {
    Scene s = FloorOnly(4.0, 3.0);
    AddBox(&s, Category::kCabinet, Vector3d(1.5, 0.0, 0.0), Vector3d(2.5, 1.0, 1.0));
    AddBox(&s, Category::kCabinet, Vector3d(1.5, 1.0 + gap, 0.0), Vector3d(2.5, 3.0, 1.0));
    return s;
  };
  EXPECT_TRUE(CheckFreeFloor(corridor(0.8)).ok);
  EXPECT_EQ(CheckFreeFloor(corridor(0.8)).num_components, 1);
  EXPECT_EQ(CheckFreeFloor(corridor(0.7)).num_components, 2);
  EXPECT_FALSE(CheckFreeFloor(corridor(0.7)).ok);
}

TEST(FloorCheckTest, ObjectsOutsideTheRobotBandDoNotBlock) {
  // A lintel above 1.9 m and a rug below 2 cm leave the passage open.
  Scene s = FloorOnly(4.0, 3.0);
  AddBox(&s, Category::kWall, Vector3d(1.9, 0.0, 0.0), Vector3d(2.1, 2.0, 2.5));
  AddBox(&s, Category::kWall, Vector3d(1.9, 2.0, 2.0), Vector3d(2.1, 3.0, 2.5));
  AddBox(&s, Category::kOther, Vector3d(1.0, 2.0, 0.0), Vector3d(3.0, 3.0, 0.01));
  EXPECT_EQ(CheckFreeFloor(s).num_components, 1);
  // A table top across the gap blocks it.
  AddBox(&s, Category::kTable, Vector3d(1.8, 2.0, 0.7), Vector3d(2.2, 3.0, 0.75));
  EXPECT_EQ(CheckFreeFloor(s).num_components, 2);
}

TEST(FloorCheckTest, FlagsObjectsOutOfReach) {
  // A dead-end corridor 0.6 m wide (too narrow for the robot) with a radio at its far end.
  Scene s = FloorOnly(6.0, 3.0);
  AddBox(&s, Category::kWall, Vector3d(3.0, 0.6, 0.0), Vector3d(6.0, 3.0, 2.5));
  const auto far = AddBox(&s, Category::kRadio, Vector3d(5.7, 0.2, 0.0), Vector3d(5.9, 0.4, 0.2));
  const auto near = AddBox(&s, Category::kChair, Vector3d(1.0, 1.0, 0.0), Vector3d(1.5, 1.5, 0.9));
  const FloorConnectivityReport r = CheckFreeFloor(s);
  EXPECT_EQ(r.num_components, 1);
  ASSERT_EQ(r.unreachable_instances.size(), 1u);
  EXPECT_EQ(r.unreachable_instances[0], far);
  EXPECT_NE(r.unreachable_instances[0], near);
  EXPECT_FALSE(r.ok);
}

TEST(FloorCheckTest, LShapedFloorIsRasterisedFromItsTriangles) {
  Scene s("L");
  SceneObject floor;
  floor.category = Category::kFloor;
  geometry::Append(geometry::MakeQuadXY(0, 0, 4, 2), &floor.mesh);
  geometry::Append(geometry::MakeQuadXY(0, 2, 2, 4), &floor.mesh);
  s.Add(floor);
  const FloorConnectivityReport r = CheckFreeFloor(s, 0.05);
  EXPECT_EQ(r.floor_cells, 80u * 40u + 40u * 40u);
  EXPECT_EQ(r.num_components, 1);
}

TEST(FloorCheckTest, RejectsBadInput) {
  EXPECT_THROW(CheckFreeFloor(Scene("empty")), InputError);
  EXPECT_THROW(CheckFreeFloor(FloorOnly(1, 1), 0.0), InputError);
}

}  // namespace
}  // namespace objscan::world::procedural
