#include "objscan/io/category_map.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"
#include "objscan/io/suncg_categories.h"
#include "objscan/io/test_util.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;
using testing::WriteText;
using world::Category;

ModelIdentity Named(const std::string& name, const std::vector<std::string>& uris = {}) {
  ModelIdentity m;
  m.name = name;
  m.uris = uris;
  return m;
}

ModelIdentity Labelled(const std::string& label) {
  ModelIdentity m;
  m.name = label + "_0";
  m.labels = {label};
  return m;
}

TEST(CategoryMapTest, FirstMatchingRuleWinsAndPatternsIgnoreCase) {
  TempDir dir;
  WriteText(dir.File("map.yaml"),
            "rules:\n"
            "  - {name: '^night', category: night_stand}\n"
            "  - {name: 'stand', category: tv_stand}\n"
            "  - {uri: 'bed', name: 'Frame', category: bed}\n"  // both must match
            "  - {label: '^chair$', category: chair}\n");
  const CategoryMap map = CategoryMap::Load(dir.File("map.yaml"));
  EXPECT_EQ(map.NumRules(), 4u);
  EXPECT_EQ(map.Lookup(Named("NightStand_01")), Category::kNightStand);  // rule 1 before rule 2
  EXPECT_EQ(map.Lookup(Named("TvStand")), Category::kTvStand);
  EXPECT_EQ(map.Lookup(Named("frame_2", {"model://x", "model://Bed_01/a.dae"})), Category::kBed);
  EXPECT_EQ(map.Lookup(Named("frame_2", {"model://x"})), std::nullopt);
  EXPECT_EQ(map.Lookup(Labelled("chair")), Category::kChair);
  EXPECT_EQ(map.Lookup(Labelled("office chair")), std::nullopt);
  EXPECT_EQ(map.Lookup(Named("chair")), std::nullopt);  // a name is not a label
}

TEST(CategoryMapTest, SkipRulesLeaveModelsOut) {
  TempDir dir;
  WriteText(dir.File("map.yaml"),
            "rules:\n"
            "  - {label: '^Vehicles$', category: skip}\n"
            "  - {name: 'car', category: other}\n");
  const CategoryMap map = CategoryMap::Load(dir.File("map.yaml"));
  ModelIdentity car = Named("Sports car");
  car.labels = {"Vehicles"};
  const std::optional<CategoryRuleMatch> skipped = map.Match(car);
  ASSERT_TRUE(skipped.has_value());
  EXPECT_TRUE(skipped->skip);
  EXPECT_FALSE(skipped->category.has_value());
  EXPECT_EQ(map.Lookup(car), std::nullopt);  // scene loaders: as unmatched
  const std::optional<CategoryRuleMatch> model = map.Match(Named("Car model"));
  ASSERT_TRUE(model.has_value());
  EXPECT_FALSE(model->skip);
  EXPECT_EQ(model->category, Category::kOther);
  EXPECT_EQ(map.Match(Named("Chair")), std::nullopt);
  WriteText(dir.File("bad.yaml"), "rules:\n  - {name: 'a', category: skipped}\n");
  ExpectInputError([&] { CategoryMap::Load(dir.File("bad.yaml")); }, "unknown category 'skipped' (a category name or 'skip')");
}

TEST(CategoryMapTest, IncludedMapsComeFirstInOrder) {
  TempDir dir;
  WriteText(dir.File("a.yaml"), "rules:\n  - {name: 'x', category: chair}\n");
  WriteText(dir.File("sub/b.yaml"), "rules:\n  - {name: 'x', category: sofa}\n  - {name: 'y', category: sofa}\n");
  WriteText(dir.File("main.yaml"), "include: [a.yaml, sub/b.yaml]\nrules:\n  - {name: '.', category: ceiling}\n");
  const CategoryMap map = CategoryMap::Load(dir.File("main.yaml"));
  EXPECT_EQ(map.Lookup(Named("x")), Category::kChair);
  EXPECT_EQ(map.Lookup(Named("y")), Category::kSofa);
  EXPECT_EQ(map.Lookup(Named("z")), Category::kCeiling);
}

TEST(CategoryMapTest, SuncgRuleLooksUpTheModelIdBesideTheScene) {
  TempDir dir;
  WriteText(dir.File("data/ModelCategoryMapping.csv"),
            "index,model_id,fine_grained_class,coarse_grained_class,empty_struct_obj,nyuv2_40class,wnsynsetid,wnsynsetkey\n"
            "1,m1,armchair,chair,2,chair,n1,x\n");
  WriteText(dir.File("table.csv"), "suncg_class,category\narmchair,chair\n*,other\n");
  WriteText(dir.File("map.yaml"), "rules:\n  - {suncg: table.csv}\n");
  const CategoryMap map = CategoryMap::Load(dir.File("map.yaml"));
  ModelIdentity m = Named("m1_0");
  m.model_id = "m1";
  m.source_dir = dir.File("data/house/room");
  EXPECT_EQ(map.Lookup(m), Category::kChair);
  m.model_id = "m2";  // not in the mapping: the rule does not match
  EXPECT_EQ(map.Lookup(m), std::nullopt);
  m.model_id = "m1";
  m.source_dir = dir.File("elsewhere");  // no ModelCategoryMapping.csv above
  EXPECT_EQ(map.Lookup(m), std::nullopt);
}

TEST(CategoryMapTest, MalformedMapsNameFileAndRule) {
  TempDir dir;
  const struct {
    std::string text;
    std::string needle;
  } cases[] = {
      {"rules:\n  - {name: 'a', category: throne}\n", "rule 1: unknown category 'throne'"},
      {"rules:\n  - {name: 'a(', category: chair}\n", "rule 1: name 'a(' is not a valid regular expression"},
      {"rules:\n  - {name: 'a', category: chair}\n  - {nmae: 'b', category: chair}\n", "rule 2: unknown key 'nmae'"},
      {"rules:\n  - {category: chair}\n", "rule 1: a rule needs a pattern"},
      {"rules:\n  - {name: 'a'}\n", "rule 1: a rule needs a pattern (name, uri or label) and a category"},
      {"rules:\n  - {suncg: nowhere.csv}\n", "nowhere.csv not found"},
      {"rules:\n  - {suncg: map.yaml, category: chair}\n", "a 'suncg' rule has no other keys"},
      {"rule:\n  - {name: 'a', category: chair}\n", "unknown key 'rule'"},
      {"rules: {name: 'a'}\n", "'rules' must be a list"},
      {"rules: [\n", "malformed YAML"},
      {"include: map.yaml\n", "include cycle"},
      {"include: [missing.yaml]\n", "map.yaml: included category map"},
  };
  for (const auto& c : cases) {
    WriteText(dir.File("map.yaml"), c.text);
    SCOPED_TRACE(c.text);
    ExpectInputError([&] { CategoryMap::Load(dir.File("map.yaml")); }, c.needle);
    ExpectInputError([&] { CategoryMap::Load(dir.File("map.yaml")); }, "map.yaml");
  }
  ExpectInputError([&] { ResolveCategoryMapPath(dir.File("none.yaml")); }, "none.yaml: category map not found");
}

TEST(CategoryMapTest, ShippedMapsResolveAgainstTheConfigFolder) {
  for (const char* name : {"categories/default.yaml", "categories/suncg.yaml", "categories/aws-robomaker.yaml",
                           "categories/scannet.yaml", "categories/sweethome3d.yaml"}) {
    SCOPED_TRACE(name);
    const std::string path = ResolveCategoryMapPath(name);
    EXPECT_EQ(path, ConfigDir() + "/" + name);
    EXPECT_GT(CategoryMap::Load(path).NumRules(), 0u);
  }
}

// Every model folder of the AWS RoboMaker small house (aws-small-house/models), as the world's
// <include> URIs name them, and the category the shipped map gives.
TEST(CategoryMapTest, AwsRobomakerMapCoversEverySmallHouseModel) {
  const CategoryMap map = CategoryMap::Load(ResolveCategoryMapPath("categories/aws-robomaker.yaml"));
  const std::pair<const char*, Category> expected[] = {
      {"AirconditionerA_01", Category::kOther},  {"AirconditionerB_01", Category::kOther},
      {"BalconyTable_01", Category::kTable},     {"Ball_01", Category::kOther},
      {"Bed_01", Category::kBed},                {"Board_01", Category::kOther},
      {"Carpet_01", Category::kOther},           {"ChairA_01", Category::kChair},
      {"ChairD_01", Category::kChair},           {"Chandelier_01", Category::kLamp},
      {"CoffeeTable_01", Category::kTable},      {"CookingBench_01", Category::kCabinet},
      {"Curtain_01", Category::kCurtain},        {"DeskPortraitA_01", Category::kOther},
      {"DeskPortraitA_02", Category::kOther},    {"DeskPortraitB_01", Category::kOther},
      {"DeskPortraitB_02", Category::kOther},    {"DeskPortraitC_01", Category::kOther},
      {"DeskPortraitC_02", Category::kOther},    {"DeskPortraitD_01", Category::kOther},
      {"DeskPortraitD_02", Category::kOther},    {"DeskPortraitD_03", Category::kOther},
      {"DeskPortraitD_04", Category::kOther},    {"Door_01", Category::kDoor},
      {"Dumbbell_01", Category::kOther},         {"FitnessEquipment_01", Category::kOther},
      {"FloorB_01", Category::kFloor},           {"FoldingDoor_01", Category::kDoor},
      {"FoldingDoor_02", Category::kDoor},       {"Handle_01", Category::kOther},
      {"HouseWallB_01", Category::kWall},        {"KitchenCabinet_01", Category::kCabinet},
      {"KitchenTable_01", Category::kTable},     {"KitchenUtensils_01", Category::kOther},
      {"LightC_01", Category::kLamp},            {"NightStand_01", Category::kNightStand},
      {"Pillow_01", Category::kOther},           {"PortraitA_01", Category::kOther},
      {"PortraitA_02", Category::kOther},        {"PortraitB_01", Category::kOther},
      {"PortraitB_02", Category::kOther},        {"PortraitB_03", Category::kOther},
      {"PortraitC_01", Category::kOther},        {"PortraitD_01", Category::kOther},
      {"PortraitD_02", Category::kOther},        {"PortraitE_01", Category::kOther},
      {"PortraitE_02", Category::kOther},        {"Quilt_01", Category::kOther},
      {"Rangehood_01", Category::kOther},        {"ReadingDesk_01", Category::kDesk},
      {"Refrigerator_01", Category::kRefrigerator}, {"RoomCeiling_01", Category::kCeiling},
      {"RoomWall_01", Category::kWall},          {"RoomWindow_01", Category::kWindow},
      {"SeasoningBox_01", Category::kOther},     {"SecurityCamera_01", Category::kOther},
      {"ShoeRack_01", Category::kCabinet},       {"SofaB_01", Category::kSofa},
      {"SofaC_01", Category::kSofa},             {"Sofa_01", Category::kSofa},
      {"TVCabinet_01", Category::kTvStand},      {"TV_01", Category::kMonitor},
      {"TV_02", Category::kMonitor},             {"Tablet_01", Category::kOther},
      {"Tableware_01", Category::kOther},        {"Trash_01", Category::kCan},
      {"Vase_01", Category::kOther},             {"Wardrobe_01", Category::kCabinet},
  };
  EXPECT_EQ(std::size(expected), 68u);
  for (const auto& [name, category] : expected) {
    const std::string model = std::string("aws_robomaker_residential_") + name;
    const ModelIdentity m = Named(std::string(name) + "_001", {"model://" + model, "model://" + model + "/meshes/x.DAE"});
    EXPECT_EQ(map.Lookup(m), category) << name;
  }
  // Retail (bookstore) names follow the same words.
  EXPECT_EQ(map.Lookup(Named("s", {"model://aws_robomaker_retail_ShelfA_01"})), Category::kShelves);
  // Other worlds' models are not claimed.
  EXPECT_EQ(map.Lookup(Named("Bed_01_001", {"model://bed"})), std::nullopt);
}

TEST(CategoryMapTest, ScanNetMapGivesNyu40AndRawLabelsTheirCategories) {
  const CategoryMap map = CategoryMap::Load(ResolveCategoryMapPath("categories/scannet.yaml"));
  const std::pair<const char*, Category> expected[] = {
      {"wall", Category::kWall},           {"floor", Category::kFloor},          {"ceiling", Category::kCeiling},
      {"cabinet", Category::kCabinet},     {"kitchen cabinets", Category::kCabinet}, {"bed", Category::kBed},
      {"chair", Category::kChair},         {"office chair", Category::kChair},   {"armchair", Category::kChair},
      {"sofa", Category::kSofa},           {"couch", Category::kSofa},           {"table", Category::kTable},
      {"coffee table", Category::kTable},  {"door", Category::kDoor},            {"window", Category::kWindow},
      {"bookshelf", Category::kShelves},   {"shelves", Category::kShelves},      {"counter", Category::kCabinet},
      {"desk", Category::kDesk},           {"curtain", Category::kCurtain},      {"shower curtain", Category::kCurtain},
      {"dresser", Category::kDresser},     {"refrigerator", Category::kRefrigerator}, {"mini fridge", Category::kRefrigerator},
      {"television", Category::kMonitor},  {"tv", Category::kMonitor},           {"monitor", Category::kMonitor},
      {"night stand", Category::kNightStand}, {"nightstand", Category::kNightStand}, {"toilet", Category::kToilet},
      {"toilet paper", Category::kOther},  {"sink", Category::kSink},            {"lamp", Category::kLamp},
      {"table lamp", Category::kLamp},     {"bathtub", Category::kBathtub},      {"trash can", Category::kCan},
      {"tv stand", Category::kTvStand},    {"picture", Category::kOther},        {"pillow", Category::kOther},
      {"otherfurniture", Category::kOther}, {"otherprop", Category::kOther},     {"otherstructure", Category::kOther},
  };
  for (const auto& [label, category] : expected) EXPECT_EQ(map.Lookup(Labelled(label)), category) << label;
  EXPECT_EQ(map.Lookup(Labelled("ukulele")), std::nullopt);  // unknown raw labels are listed by the loader
}

TEST(CategoryMapTest, CategoryFromNameKeepsObjectCategoriesOnly) {
  EXPECT_EQ(CategoryFromName("chair_2"), Category::kChair);
  EXPECT_EQ(CategoryFromName("night_stand"), Category::kNightStand);
  EXPECT_EQ(CategoryFromName("wall_1"), std::nullopt);  // structure needs a rule
  EXPECT_EQ(CategoryFromName("Bed_01_001"), std::nullopt);
}

}  // namespace
}  // namespace objscan::io
