// The ten OASC development worlds of ../shared/data/oasc-dev load completely and make sense.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <sstream>

#include "objscan/io/gazebo_world.h"
#include "objscan/io/scene_spec.h"
#include "shared_data.h"

namespace objscan::io {
namespace {

struct WorldCase {
  const char* folder;  // below oasc-dev/SUNCG
  std::size_t walls;   // valve_wall* models, counted in the world file
  std::size_t furniture;  // every other <model> except ground_plane
};

// Counted by hand from the <model name=...> elements of each room.world.
const WorldCase kWorlds[] = {
    {"bathroom/0a2f9f9b603e3960459f332c5635051e/0_3", 24, 7},
    {"bathroom/3257c4594a86e0e63e685e5bd7a54996/1_2", 17, 9},
    {"bedroom/0a2f9f9b603e3960459f332c5635051e/0_7", 31, 18},
    {"bedroom/19756a992ac80fb46e8b44493e3b2386/1_9", 24, 8},
    {"kitchen/13f8a2df1193f4768531d4b2cfa7e4d5/0_10", 28, 19},
    {"kitchen/250461bb26d6556bd0074c695ee9b010/0_4", 26, 17},
    {"living_room/20bb3f81a2161f2f3d533afe221767cf/0_5", 46, 28},
    {"living_room/245e4e571641cf25476c50a05b499641/0_3", 30, 9},
    {"office/2e42bc113281da42ae5fb68925a2c896/0_3", 30, 21},
    {"office/470373ce3ac494b055bb0a14232552d0/0_2", 19, 14},
};

constexpr double kWallHeightM = 2.4384;
constexpr double kWallWidthM = 1.2192;

std::string WorldPath(const std::string& data, const WorldCase& w) {
  return data + "/oasc-dev/SUNCG/" + w.folder + "/room.world";
}

// Loading all ten takes a few seconds; each world is loaded once for all tests.
const world::Scene& Loaded(const std::string& data, const WorldCase& w) {
  static std::map<std::string, std::unique_ptr<world::Scene>> cache;
  auto& slot = cache[w.folder];
  if (!slot) {
    SceneLoadOptions options;
    options.model_path = data + "/gazebo-models";
    slot = std::make_unique<world::Scene>(LoadScene(WorldPath(data, w), options));
  }
  return *slot;
}

geometry::Aabb3 WallExtent(const world::Scene& scene) {
  geometry::Aabb3 walls;
  for (const auto& o : scene.objects()) {
    if (o.category == world::Category::kWall) walls.Extend(scene.ObjectBounds(o));
  }
  return walls;
}

TEST(OascWorldsTest, AllTenLoadWithTheRightObjectCounts) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  for (const WorldCase& w : kWorlds) {
    SCOPED_TRACE(w.folder);
    const world::Scene& scene = Loaded(data, w);
    EXPECT_TRUE(scene.missing_meshes().empty());
    EXPECT_EQ(scene.objects().size(), 1 + w.walls + w.furniture);
    EXPECT_EQ(scene.NumFurniture(), w.furniture);
    std::size_t walls = 0, floors = 0;
    for (const auto& o : scene.objects()) {
      walls += o.category == world::Category::kWall;
      floors += o.category == world::Category::kFloor;
      EXPECT_FALSE(o.mesh.Empty()) << o.name;
    }
    EXPECT_EQ(walls, w.walls);
    EXPECT_EQ(floors, 1u);
  }
}

TEST(OascWorldsTest, FurnitureRestsOnTheFloorInsideTheWalls) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  for (const WorldCase& w : kWorlds) {
    SCOPED_TRACE(w.folder);
    const world::Scene& scene = Loaded(data, w);
    const geometry::Aabb3 walls = WallExtent(scene);
    ASSERT_FALSE(walls.Empty());
    const geometry::Aabb3 floor = scene.ObjectBounds(scene.objects()[0]);
    EXPECT_NEAR(floor.min_m.z(), 0.0, 1e-6);
    EXPECT_NEAR(floor.max_m.z(), 0.0, 1e-6);
    EXPECT_TRUE(floor.Contains(Eigen::Vector3d(walls.min_m.x(), walls.min_m.y(), 0.0)));
    EXPECT_TRUE(floor.Contains(Eigen::Vector3d(walls.max_m.x(), walls.max_m.y(), 0.0)));
    for (const auto& o : scene.objects()) {
      if (o.IsStructural()) continue;
      const geometry::Aabb3 b = scene.ObjectBounds(o);
      EXPECT_GE(b.min_m.z(), -0.03) << o.name;
      // Doors stand in the wall line and their open leaf swings out of the room.
      const double tol_m = o.category == world::Category::kDoor ? 1.0 : 0.1;
      EXPECT_GE(b.min_m.x(), walls.min_m.x() - tol_m) << o.name;
      EXPECT_GE(b.min_m.y(), walls.min_m.y() - tol_m) << o.name;
      EXPECT_LE(b.max_m.x(), walls.max_m.x() + tol_m) << o.name;
      EXPECT_LE(b.max_m.y(), walls.max_m.y() + tol_m) << o.name;
      EXPECT_LE(b.max_m.z(), 3.0) << o.name;  // chandeliers hang above the 2.44 m wall panels
    }
  }
}

TEST(OascWorldsTest, WallsStandUpright) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  for (const WorldCase& w : kWorlds) {
    SCOPED_TRACE(w.folder);
    const world::Scene& scene = Loaded(data, w);
    for (const auto& o : scene.objects()) {
      if (o.category != world::Category::kWall) continue;
      const geometry::Aabb3 local = geometry::Bounds(o.mesh);  // model frame
      EXPECT_NEAR(local.Size().z(), kWallHeightM, 2e-3) << o.name;
      // Some worlds turn the panel inside the model (visual yaw 90 deg): compare the footprint's sides.
      EXPECT_NEAR(std::max(local.Size().x(), local.Size().y()), kWallWidthM, 2e-3) << o.name;
      EXPECT_LT(std::min(local.Size().x(), local.Size().y()), 0.02) << o.name;
      const geometry::Aabb3 b = scene.ObjectBounds(o);
      EXPECT_NEAR(b.min_m.z(), 0.0, 1e-3) << o.name;
      EXPECT_NEAR(b.Size().z(), kWallHeightM, 2e-3) << o.name;
      EXPECT_LT(std::min(b.Size().x(), b.Size().y()), 0.02) << o.name;  // axis-aligned panels
    }
  }
}

// Reads model_id -> fine_grained_class straight from the CSV (independently of the loader).
std::map<std::string, std::string> FineClasses(const std::string& csv) {
  std::map<std::string, std::string> fine;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string index, id, cls;
    std::getline(ss, index, ',');
    std::getline(ss, id, ',');
    std::getline(ss, cls, ',');
    fine[id] = cls;
  }
  return fine;
}

TEST(OascWorldsTest, CategoriesFollowTheCsv) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  const auto fine = FineClasses(data + "/oasc-dev/SUNCG/ModelCategoryMapping.csv");
  // Spot checks: SUNCG id -> fine class in ModelCategoryMapping.csv -> our category by
  // config/suncg_categories.csv.
  struct Check {
    const char* id;
    const char* fine_class;
    world::Category category;
  };
  const Check checks[] = {
      {"403", "double_bed", world::Category::kBed},          {"78", "single_bed", world::Category::kBed},
      {"89", "chair", world::Category::kChair},              {"348", "armchair", world::Category::kChair},
      {"106", "office_chair", world::Category::kChair},      {"102", "refrigerator", world::Category::kRefrigerator},
      {"92", "kitchen_cabinet", world::Category::kCabinet},  {"250", "hanging_kitchen_cabinet", world::Category::kCabinet},
      {"121", "wardrobe_cabinet", world::Category::kCabinet}, {"191", "bookshelf", world::Category::kShelves},
      {"207", "shelving", world::Category::kShelves},        {"71", "coffee_table", world::Category::kTable},
      {"111", "television", world::Category::kMonitor},      {"189", "computer", world::Category::kMonitor},
      {"115", "tv_stand", world::Category::kTvStand},        {"146", "stand", world::Category::kNightStand},
      {"82", "bathtub", world::Category::kBathtub},          {"83", "toilet", world::Category::kToilet},
      {"181", "sink", world::Category::kSink},               {"747", "curtain", world::Category::kCurtain},
      {"122", "door", world::Category::kDoor},               {"212", "window", world::Category::kWindow},
      {"419", "table_lamp", world::Category::kLamp},         {"630", "chandelier", world::Category::kLamp},
      {"156", "sofa", world::Category::kSofa},               {"105", "desk", world::Category::kDesk},
      {"218", "stereo_set", world::Category::kRadio},        {"153", "rug", world::Category::kOther},
      {"130", "plant", world::Category::kOther},
  };
  std::map<std::string, int> seen;
  for (const WorldCase& w : kWorlds) {
    const world::Scene& scene = Loaded(data, w);
    for (const auto& o : scene.objects()) {
      for (const Check& c : checks) {
        if (o.model_name != c.id) continue;
        ++seen[c.id];
        EXPECT_EQ(fine.at(c.id), c.fine_class) << c.id;
        EXPECT_EQ(o.category, c.category) << o.name << " in " << w.folder;
      }
      if (!o.IsStructural()) {
        EXPECT_TRUE(fine.count(o.model_name)) << o.model_name << " not in the CSV";
      }
    }
  }
  for (const Check& c : checks) EXPECT_GT(seen[c.id], 0) << c.id << " occurs in no world";
}

TEST(OascWorldsTest, FootprintsMatchTheWorldsCollisionBoxes) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  // Each SUNCG <model> of a world file has a collision <box><size>sx sy 2</size> in its model frame
  // (the link and visual poses are identity): sx, sy are the mesh footprint when the Y_UP COLLADA
  // meshes are read as Gazebo reads them.
  // The first 3-number <size> inside each <model> element (never crossing its </model>).
  const std::regex model_re(
      "<model name='([^']+)'>(?:(?!</model>)[\\s\\S])*?<size>([-0-9.e]+) ([-0-9.e]+) ([-0-9.e]+)</size>");
  int checked = 0;
  for (const WorldCase& w : kWorlds) {
    SCOPED_TRACE(w.folder);
    const world::Scene& scene = Loaded(data, w);
    std::ifstream in(WorldPath(data, w));
    std::stringstream text;
    text << in.rdbuf();
    const std::string world_text = text.str();
    for (auto it = std::sregex_iterator(world_text.begin(), world_text.end(), model_re); it != std::sregex_iterator();
         ++it) {
      const std::string name = (*it)[1];
      if (name == "ground_plane" || name.rfind("valve_wall", 0) == 0) continue;
      const world::SceneObject* object = nullptr;
      for (const auto& o : scene.objects()) {
        if (o.name == name) object = &o;
      }
      ASSERT_NE(object, nullptr) << name;
      const geometry::Aabb3 local = geometry::Bounds(object->mesh);
      const double sx = std::stod((*it)[2]), sy = std::stod((*it)[3]);
      EXPECT_NEAR(local.Size().x(), sx, 0.02 + 0.02 * sx) << name;
      EXPECT_NEAR(local.Size().y(), sy, 0.02 + 0.02 * sy) << name;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 7 + 9 + 18 + 8 + 19 + 17 + 28 + 9 + 21 + 14);
}

}  // namespace
}  // namespace objscan::io

namespace objscan::io {
namespace {

// The shipped SUNCG map alone gives every OASC object the category the default map gives (which is
// the mapping of before category maps: the scene snapshots of all ten worlds were byte-identical), and
// no OASC model is left unmapped.
TEST(OascWorldsTest, SuncgMapAloneGivesTheSameCategories) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  for (const WorldCase& w : kWorlds) {
    SCOPED_TRACE(w.folder);
    SceneLoadOptions options;
    options.model_path = data + "/gazebo-models";
    options.category_map = "categories/suncg.yaml";
    const world::Scene suncg = LoadScene(WorldPath(data, w), options);
    const world::Scene& by_default = Loaded(data, w);
    ASSERT_EQ(suncg.objects().size(), by_default.objects().size());
    for (std::size_t i = 0; i < suncg.objects().size(); ++i) {
      EXPECT_EQ(suncg.objects()[i].name, by_default.objects()[i].name);
      EXPECT_EQ(suncg.objects()[i].category, by_default.objects()[i].category) << suncg.objects()[i].name;
    }
    EXPECT_TRUE(by_default.unmapped_models().empty()) << by_default.unmapped_models().front();
  }
}

}  // namespace
}  // namespace objscan::io
