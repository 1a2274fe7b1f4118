#include "objscan/eval/rooms.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "objscan/common/error.h"
#include "objscan/geometry/mesh.h"
#include "objscan/io/scene_spec.h"
#include "shared_data.h"

namespace objscan::eval {
namespace {

using world::Category;

void AddBox(world::Scene* scene, Category category, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  world::SceneObject o;
  o.category = category;
  o.mesh = geometry::MakeBox(lo, hi);
  scene->Add(std::move(o));
}

// Two 4 m x 4 m rooms side by side (x 0-4 and 4-8), walls 0.1 m thick and 2.5 m high, the wall
// between them open over `opening_m` around y = 2; with `door`, a door panel stands in the opening.
// A chair in the west room, a table in the east one.
world::Scene TwoRooms(double opening_m, bool door) {
  const double lo = 2.0 - 0.5 * opening_m, hi = 2.0 + 0.5 * opening_m;
  world::Scene scene("two rooms");
  world::SceneObject floor;
  floor.category = Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(0.0, 0.0, 8.0, 4.0);
  scene.Add(std::move(floor));
  AddBox(&scene, Category::kWall, {-0.1, -0.1, 0.0}, {8.1, 0.0, 2.5});
  AddBox(&scene, Category::kWall, {-0.1, 4.0, 0.0}, {8.1, 4.1, 2.5});
  AddBox(&scene, Category::kWall, {-0.1, 0.0, 0.0}, {0.0, 4.0, 2.5});
  AddBox(&scene, Category::kWall, {8.0, 0.0, 0.0}, {8.1, 4.0, 2.5});
  AddBox(&scene, Category::kWall, {3.95, 0.0, 0.0}, {4.05, lo, 2.5});
  AddBox(&scene, Category::kWall, {3.95, hi, 0.0}, {4.05, 4.0, 2.5});
  AddBox(&scene, Category::kWall, {3.95, lo, 2.1}, {4.05, hi, 2.5});  // lintel: no cut
  if (door) AddBox(&scene, Category::kDoor, {3.98, lo, 0.0}, {4.02, hi, 2.05});
  AddBox(&scene, Category::kChair, {0.2, 0.2, 0.0}, {0.7, 0.7, 0.9});
  AddBox(&scene, Category::kTable, {7.0, 3.0, 0.0}, {7.8, 3.8, 0.75});
  return scene;
}

TEST(RoomPartitionTest, DoorsAndDoorwaysSeparateRoomsAndAWideOpeningJoinsThem) {
  for (bool door : {true, false}) {
    // A 1 m opening: a doorway, with or without its door.
    const RoomPartition rooms = RoomPartition::FromScene(TwoRooms(1.0, door));
    ASSERT_EQ(rooms.rooms().size(), 2u) << "door " << door;
    const int west = rooms.RoomAt(1.0, 2.0), east = rooms.RoomAt(6.0, 2.0);
    ASSERT_GE(west, 0);
    ASSERT_GE(east, 0);
    EXPECT_NE(west, east);
    for (const Room& r : rooms.rooms()) {
      // 16 m2 less the cells under the walls; the doorway's cells go to one side or the other.
      EXPECT_GT(r.area_m2, 14.0);
      EXPECT_LE(r.area_m2, 16.5);
    }
    EXPECT_NEAR(rooms.rooms()[static_cast<std::size_t>(west)].center_m.x(), 2.0, 0.15);
    EXPECT_NEAR(rooms.rooms()[static_cast<std::size_t>(east)].center_m.x(), 6.0, 0.15);
    // Something standing in the doorway belongs to the nearest room within half a metre.
    const int at_door = rooms.RoomAt(4.0, 2.0);
    EXPECT_TRUE(at_door == west || at_door == east);
    EXPECT_EQ(rooms.RoomAt(30.0, 30.0), -1);
    // The doorway is near both rooms; each room's middle only near itself.
    const std::vector<int> both = {std::min(west, east), std::max(west, east)};
    EXPECT_EQ(rooms.RoomsWithin(4.0, 2.0, 0.5), both);
    EXPECT_EQ(rooms.RoomsWithin(1.0, 2.0, 0.5), std::vector<int>{west});
    EXPECT_TRUE(rooms.RoomsWithin(30.0, 30.0, 0.5).empty());
    if (door) {
      EXPECT_EQ(rooms.RoomAt(4.0, 2.0, 0.0), -1) << "the door's own cells are in no room";
    }
  }
  // A 2 m wide opening joins the two halves into one room.
  const RoomPartition open = RoomPartition::FromScene(TwoRooms(2.0, false));
  ASSERT_EQ(open.rooms().size(), 1u);
  EXPECT_GT(open.rooms()[0].area_m2, 29.0);
  EXPECT_EQ(open.RoomAt(1.0, 2.0), open.RoomAt(6.0, 2.0));
}

TEST(RoomPartitionTest, NoFloorOrNoFurnitureMeansNoRoomAndBadOptionsAreRejected) {
  world::Scene no_floor;
  AddBox(&no_floor, Category::kChair, {0.0, 0.0, 0.0}, {0.5, 0.5, 0.9});
  EXPECT_TRUE(RoomPartition::FromScene(no_floor).rooms().empty());
  world::Scene empty_room;
  world::SceneObject floor;
  floor.category = Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(0.0, 0.0, 4.0, 4.0);
  empty_room.Add(std::move(floor));
  EXPECT_TRUE(RoomPartition::FromScene(empty_room).rooms().empty());
  RoomPartitionOptions bad;
  bad.cell_m = 0.0;
  EXPECT_THROW(RoomPartition::FromScene(TwoRooms(1.0, true), bad), ConfigError);
}

// The AWS small house: its open plan (bedroom, living and dining room joined by openings of 3 m and
// more) is one room; rooms behind narrower doorways are rooms of their own; the floor quad around
// the house joins none. Every chair and the bed are in some room.
TEST(RoomPartitionTest, TheAwsSmallHouseSplitsAtItsDoorways) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  io::SceneLoadOptions load;
  load.model_path = data + "/aws-small-house/models";
  const world::Scene house = io::LoadScene(data + "/aws-small-house/worlds/small_house.world", load);
  const RoomPartition rooms = RoomPartition::FromScene(house);
  std::vector<int> objects_in(rooms.rooms().size(), 0);
  int sofa_room = -1;
  for (const auto& o : house.objects()) {
    if (o.IsStructural()) continue;
    const Eigen::Vector3d c = house.ObjectBounds(o).Center();
    const int r = rooms.RoomAt(c.x(), c.y());
    if (r >= 0) ++objects_in[static_cast<std::size_t>(r)];
    if (o.category == Category::kSofa) sofa_room = r;
    if (o.category == Category::kChair || o.category == Category::kBed) {
      EXPECT_GE(r, 0) << o.name;
    }
  }
  int furnished = 0;
  for (const Room& r : rooms.rooms()) {
    std::printf("[ info ] room %d: %.1f m2 at (%.1f, %.1f), %d objects\n", r.id, r.area_m2, r.center_m.x(),
                r.center_m.y(), objects_in[static_cast<std::size_t>(r.id)]);
    if (objects_in[static_cast<std::size_t>(r.id)] > 0) ++furnished;
  }
  EXPECT_GE(furnished, 2);
  EXPECT_EQ(sofa_room, 0) << "the sofa stands in the open plan, the largest room";
  // Inside the outer walls (19 m x 11.4 m).
  double total = 0.0;
  for (const Room& r : rooms.rooms()) total += r.area_m2;
  EXPECT_LT(total, 19.0 * 11.4);
}

}  // namespace
}  // namespace objscan::eval
