#include "objscan/eval/reachability.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"
#include "objscan/geometry/mesh.h"
#include "objscan/io/scene_spec.h"

namespace objscan::eval {
namespace {

using world::Category;

void AddBox(world::Scene* scene, Category category, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
            const std::string& name = "") {
  world::SceneObject o;
  o.category = category;
  o.name = name;
  o.mesh = geometry::MakeBox(lo, hi);
  scene->Add(std::move(o));
}

// Two 4 m x 4 m rooms (x 0-4 and 4-8), walls 0.1 m thick, joined by a 1 m doorway around y = 2
// that a door closes when `door`. A chair in the west room, a table in the east one.
world::Scene TwoRooms(bool door) {
  world::Scene scene("two rooms");
  world::SceneObject floor;
  floor.category = Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(0.0, 0.0, 8.0, 4.0);
  scene.Add(std::move(floor));
  AddBox(&scene, Category::kWall, {-0.1, -0.1, 0.0}, {8.1, 0.0, 2.5});
  AddBox(&scene, Category::kWall, {-0.1, 4.0, 0.0}, {8.1, 4.1, 2.5});
  AddBox(&scene, Category::kWall, {-0.1, 0.0, 0.0}, {0.0, 4.0, 2.5});
  AddBox(&scene, Category::kWall, {8.0, 0.0, 0.0}, {8.1, 4.0, 2.5});
  AddBox(&scene, Category::kWall, {3.95, 0.0, 0.0}, {4.05, 1.5, 2.5});
  AddBox(&scene, Category::kWall, {3.95, 2.5, 0.0}, {4.05, 4.0, 2.5});
  AddBox(&scene, Category::kWall, {3.95, 1.5, 2.1}, {4.05, 2.5, 2.5});
  if (door) AddBox(&scene, Category::kDoor, {3.98, 1.5, 0.0}, {4.02, 2.5, 2.05}, "door_1");
  AddBox(&scene, Category::kChair, {0.2, 0.2, 0.0}, {0.7, 0.7, 0.9}, "chair_1");
  AddBox(&scene, Category::kTable, {7.0, 3.0, 0.0}, {7.8, 3.8, 0.75}, "table_1");
  return scene;
}

TEST(ReachabilityTest, ARoomBehindAClosedDoorIsUnreachableAndOpeningTheDoorReachesIt) {
  world::Scene closed = TwoRooms(/*door=*/true);
  const RoomPartition rooms = RoomPartition::FromScene(closed);
  ASSERT_EQ(rooms.rooms().size(), 2u);
  const int west = rooms.RoomAt(2.0, 2.0), east = rooms.RoomAt(6.0, 2.0);
  const RoomReachability reach = ReachableRooms(closed, rooms, Eigen::Vector2d(2.0, 2.0));
  ASSERT_TRUE(reach.known);
  EXPECT_TRUE(reach.Reachable(west));
  EXPECT_FALSE(reach.Reachable(east));
  EXPECT_EQ(reach.reachable_area_m2[static_cast<std::size_t>(east)], 0.0);
  // The robot's centre keeps about 0.3 m (its radius and half a cell's diagonal) from walls and
  // furniture: 3.35 m x 3.4 m of the west room less the chair's corner grown by that, 0.8 m x 0.8 m.
  EXPECT_NEAR(reach.reachable_area_m2[static_cast<std::size_t>(west)], 3.35 * 3.4 - 0.8 * 0.8, 0.3);
  // From the east room it is the other way round.
  const RoomReachability from_east = ReachableRooms(closed, rooms, Eigen::Vector2d(6.0, 2.0));
  EXPECT_FALSE(from_east.Reachable(west));
  EXPECT_TRUE(from_east.Reachable(east));

  // Doors open (the door removed, as scene.doors_open does): both rooms.
  io::OpenDoors(&closed);
  ASSERT_EQ(closed.load_notes().size(), 1u);
  EXPECT_EQ(closed.load_notes()[0], "doors open: 1 door removed (door_1)");
  const RoomPartition open_rooms = RoomPartition::FromScene(closed);
  const RoomReachability open = ReachableRooms(closed, open_rooms, Eigen::Vector2d(2.0, 2.0));
  ASSERT_TRUE(open.known);
  for (std::size_t r = 0; r < open_rooms.rooms().size(); ++r) EXPECT_TRUE(open.Reachable(static_cast<int>(r))) << r;
}

TEST(ReachabilityTest, UnknownStartOrNoRoomsCountsEverythingReachableAndBadOptionsThrow) {
  const world::Scene scene = TwoRooms(true);
  const RoomPartition rooms = RoomPartition::FromScene(scene);
  // Far outside the house there is no free floor to start from: nothing can be said.
  const RoomReachability outside = ReachableRooms(scene, rooms, Eigen::Vector2d(30.0, 30.0));
  EXPECT_FALSE(outside.known);
  EXPECT_TRUE(outside.Reachable(0));
  EXPECT_TRUE(outside.Reachable(1));
  EXPECT_FALSE(ReachableRooms(scene, RoomPartition(), Eigen::Vector2d(2.0, 2.0)).known);
  RoomReachabilityOptions bad;
  bad.robot_radius_m = 0.0;
  EXPECT_THROW(ReachableRooms(scene, rooms, Eigen::Vector2d(2.0, 2.0), bad), ConfigError);
}

}  // namespace
}  // namespace objscan::eval
