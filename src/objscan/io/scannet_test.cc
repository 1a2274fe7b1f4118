#include "objscan/io/scannet.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "objscan/common/error.h"
#include "objscan/io/scene_spec.h"
#include "objscan/io/test_util.h"
#include "scannet_fixture.h"

namespace objscan::io {
namespace {

namespace fs = std::filesystem;
using objscan::testing::ScanNetFixtureOptions;
using objscan::testing::WriteScanNetFixture;
using testing::ExpectInputError;
using testing::TempDir;
using testing::ByName;
using testing::WriteText;
using world::Category;

std::vector<const world::SceneObject*> OfCategory(const world::Scene& scene, Category c) {
  std::vector<const world::SceneObject*> out;
  for (const auto& o : scene.objects()) {
    if (o.category == c) out.push_back(&o);
  }
  return out;
}

// Compares world bounds with a fixture box; `xy` false when the scan was not given its alignment
// (levelling on the floor cannot know where the file's origin was, only where up is).
void ExpectFixtureBox(const geometry::Aabb3& b, const double* box, double tol, bool xy = true) {
  for (int k = xy ? 0 : 2; k < 3; ++k) {
    EXPECT_NEAR(b.min_m[k], box[k], tol) << "min axis " << k;
    EXPECT_NEAR(b.max_m[k], box[k + 3], tol) << "max axis " << k;
  }
  EXPECT_NEAR(b.Size().x(), box[3] - box[0], tol);
  EXPECT_NEAR(b.Size().y(), box[4] - box[1], tol);
}

TEST(ScanNetTest, AggregationGivesInstancesAndRawLabelCategoriesInTheAlignedFrame) {
  TempDir dir;
  const std::string scan = WriteScanNetFixture(dir.path().string(), "scene0001_00");
  for (const std::string& spec : {scan, scan + "/scene0001_00_vh_clean_2.ply"}) {
    SCOPED_TRACE(spec);
    ASSERT_TRUE(IsScanNetSpec(spec));
    const world::Scene scene = LoadScene(spec, SceneLoadOptions());
    EXPECT_EQ(scene.name(), "scene0001_00");
    // floor (two segments, one group), walls (four segments, one group), three objects, the rest.
    ASSERT_EQ(scene.objects().size(), 6u);
    EXPECT_EQ(OfCategory(scene, Category::kFloor).size(), 1u);
    EXPECT_EQ(OfCategory(scene, Category::kWall).size(), 1u);
    EXPECT_TRUE(scene.objects()[0].IsStructural() && scene.objects()[1].IsStructural());
    const world::SceneObject* chair = ByName(scene, "office_chair_2");
    ASSERT_NE(chair, nullptr);
    EXPECT_EQ(chair->category, Category::kChair);
    EXPECT_EQ(chair->model_name, "office chair");
    EXPECT_EQ(ByName(scene, "coffee_table_3")->category, Category::kTable);
    EXPECT_EQ(ByName(scene, "trash_can_4")->category, Category::kCan);
    EXPECT_EQ(ByName(scene, "unannotated")->category, Category::kOther);
    EXPECT_TRUE(scene.unmapped_models().empty());
    // axisAlignment undoes the tilt and the shift: the boxes are where the fixture built them (float
    // PLY coordinates: micrometres).
    ExpectFixtureBox(scene.ObjectBounds(*chair), objscan::testing::kFixtureChair, 1e-4);
    ExpectFixtureBox(scene.ObjectBounds(*ByName(scene, "coffee_table_3")), objscan::testing::kFixtureTable, 1e-4);
    const geometry::Aabb3 floor = scene.ObjectBounds(*OfCategory(scene, Category::kFloor)[0]);
    EXPECT_NEAR(floor.min_m.z(), 0.0, 1e-4);
    EXPECT_NEAR(floor.max_m.z(), 0.0, 1e-4);
  }
}

TEST(ScanNetTest, LabelsPlyGivesConnectedComponentsWithNyu40Categories) {
  TempDir dir;
  ScanNetFixtureOptions options;
  options.aggregation = false;
  const std::string scan = WriteScanNetFixture(dir.path().string(), "scene0002_00", options);
  const world::Scene scene = LoadScene(scan, SceneLoadOptions());
  ASSERT_EQ(scene.objects().size(), 6u);
  // The welded walls are one component of label 1; the trash can is NYU40 otherfurniture.
  EXPECT_EQ(ByName(scene, "wall_0")->category, Category::kWall);
  EXPECT_EQ(ByName(scene, "floor_0")->category, Category::kFloor);
  EXPECT_EQ(ByName(scene, "chair_0")->category, Category::kChair);
  EXPECT_EQ(ByName(scene, "table_0")->category, Category::kTable);
  EXPECT_EQ(ByName(scene, "otherfurniture_0")->category, Category::kOther);
  EXPECT_NE(ByName(scene, "unannotated"), nullptr);
  ExpectFixtureBox(scene.ObjectBounds(*ByName(scene, "chair_0")), objscan::testing::kFixtureChair, 1e-4);
}

TEST(ScanNetTest, WithoutAggregationPiecesOfOneLabelAreGroupedIntoObjects) {
  TempDir dir;
  using objscan::testing::kFixtureChair;
  using objscan::testing::kFixtureSecondChair;
  ScanNetFixtureOptions options;
  options.aggregation = false;
  options.split_chairs = true;  // a seat 20 cm over its base: two pieces of label chair
  {
    const world::Scene scene = LoadScene(WriteScanNetFixture(dir.path().string(), "scene0020_00", options),
                                         SceneLoadOptions());
    EXPECT_TRUE(scene.instances_inferred());
    ASSERT_EQ(OfCategory(scene, Category::kChair).size(), 1u);
    ExpectFixtureBox(scene.ObjectBounds(*ByName(scene, "chair_0")), kFixtureChair, 1e-4);
    ASSERT_EQ(scene.load_notes().size(), 1u);
    EXPECT_NE(scene.load_notes()[0].find("instances inferred"), std::string::npos) << scene.load_notes()[0];
    EXPECT_EQ(scene.objects().size(), 6u);  // floor, walls, chair, table, trash can, unannotated
  }
  options.second_chair = true;  // 20 cm beside the first: two chairs, four pieces
  {
    const world::Scene scene = LoadScene(WriteScanNetFixture(dir.path().string(), "scene0021_00", options),
                                         SceneLoadOptions());
    ASSERT_EQ(OfCategory(scene, Category::kChair).size(), 2u);
    ExpectFixtureBox(scene.ObjectBounds(*ByName(scene, "chair_0")), kFixtureChair, 1e-4);
    ExpectFixtureBox(scene.ObjectBounds(*ByName(scene, "chair_1")), kFixtureSecondChair, 1e-4);
  }
  options.split_chairs = false;
  {
    const world::Scene scene = LoadScene(WriteScanNetFixture(dir.path().string(), "scene0022_00", options),
                                         SceneLoadOptions());
    EXPECT_EQ(OfCategory(scene, Category::kChair).size(), 2u);
  }
  // With the aggregation its instances are used as they are, and nothing is inferred.
  options.aggregation = true;
  options.split_chairs = true;
  {
    const world::Scene scene = LoadScene(WriteScanNetFixture(dir.path().string(), "scene0023_00", options),
                                         SceneLoadOptions());
    EXPECT_FALSE(scene.instances_inferred());
    EXPECT_TRUE(scene.load_notes().empty());
    ASSERT_EQ(OfCategory(scene, Category::kChair).size(), 2u);
    ExpectFixtureBox(scene.ObjectBounds(*ByName(scene, "office_chair_2")), kFixtureChair, 1e-4);
  }
}

TEST(ScanNetTest, WithoutAlignmentTheFloorLabelsLevelTheScan) {
  TempDir dir;
  ScanNetFixtureOptions options;
  options.axis_alignment = false;
  options.tilt_deg = 7.0;
  const std::string scan = WriteScanNetFixture(dir.path().string(), "scene0003_00", options);
  const world::Scene scene = LoadScene(scan, SceneLoadOptions());
  const geometry::Aabb3 floor = scene.ObjectBounds(*OfCategory(scene, Category::kFloor)[0]);
  // Levelled: the 3 m deep floor, tilted by 7 deg in the file (37 cm of height), is flat at z = 0.
  EXPECT_NEAR(floor.min_m.z(), 0.0, 1e-4);
  EXPECT_NEAR(floor.max_m.z(), 0.0, 1e-4);
  EXPECT_NEAR(floor.Size().y(), objscan::testing::kFixtureRoomY, 1e-4);
  ExpectFixtureBox(scene.ObjectBounds(*ByName(scene, "office_chair_2")), objscan::testing::kFixtureChair, 1e-4, false);
  ExpectFixtureBox(scene.ObjectBounds(*ByName(scene, "coffee_table_3")), objscan::testing::kFixtureTable, 1e-4, false);
}

TEST(ScanNetTest, UnknownRawLabelsAreOtherAndListed) {
  TempDir dir;
  const std::string scan = WriteScanNetFixture(dir.path().string(), "scene0004_00");
  const std::string aggregation = scan + "/scene0004_00.aggregation.json";
  std::ifstream in(aggregation);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("coffee table"), 12, "ukulele");
  WriteText(aggregation, text);
  const world::Scene scene = LoadScene(scan, SceneLoadOptions());
  EXPECT_EQ(ByName(scene, "ukulele_3")->category, Category::kOther);
  ASSERT_EQ(scene.unmapped_models().size(), 1u);
  EXPECT_EQ(scene.unmapped_models()[0], "ukulele_3 (label 'ukulele')");
}

TEST(ScanNetTest, MalformedScansGiveOneLineNamingTheFile) {
  TempDir dir;
  const auto fresh = [&](const std::string& id, ScanNetFixtureOptions options = ScanNetFixtureOptions()) {
    return WriteScanNetFixture(dir.path().string(), id, options);
  };
  {
    const std::string scan = fresh("scene0010_00");
    WriteText(scan + "/scene0010_00_vh_clean_2.0.010000.segs.json", "{\"segIndices\": [1, 2, 3]}");
    ExpectInputError([&] { LoadScene(scan, SceneLoadOptions()); }, "segs.json: 3 segIndices for a mesh of");
  }
  {
    const std::string scan = fresh("scene0011_00");
    fs::remove(scan + "/scene0011_00_vh_clean_2.0.010000.segs.json");
    ExpectInputError([&] { LoadScene(scan, SceneLoadOptions()); }, "aggregation.json: its segments file");
  }
  {
    const std::string scan = fresh("scene0012_00");
    WriteText(scan + "/scene0012_00.aggregation.json", "{\"segGroups\": [{\"segments\": [1]}]}");
    ExpectInputError([&] { LoadScene(scan, SceneLoadOptions()); }, "aggregation.json: segGroups[0]: needs a string");
  }
  {
    const std::string scan = fresh("scene0013_00");
    WriteText(scan + "/scene0013_00.aggregation.json", "{\"segGroups\": [");
    ExpectInputError([&] { LoadScene(scan, SceneLoadOptions()); }, "aggregation.json: malformed JSON");
  }
  {
    const std::string scan = fresh("scene0014_00");
    WriteText(scan + "/scene0014_00.txt", "axisAlignment = 1 0 0 0 0 1 0 0\n");
    ExpectInputError([&] { LoadScene(scan, SceneLoadOptions()); }, "scene0014_00.txt: axisAlignment is not 16 numbers");
    WriteText(scan + "/scene0014_00.txt", "axisAlignment = 2 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n");
    ExpectInputError([&] { LoadScene(scan, SceneLoadOptions()); }, "scene0014_00.txt: axisAlignment is not a rigid");
  }
  {
    ScanNetFixtureOptions no_aggregation;
    no_aggregation.aggregation = false;
    const std::string scan = fresh("scene0015_00", no_aggregation);
    // The mesh itself (no label property) in place of labels.ply.
    fs::copy_file(scan + "/scene0015_00_vh_clean_2.ply", scan + "/scene0015_00_vh_clean_2.labels.ply",
                  fs::copy_options::overwrite_existing);
    ExpectInputError([&] { LoadScene(scan, SceneLoadOptions()); }, "labels.ply: vertices have no 'label' property");
  }
  {
    ScanNetFixtureOptions nothing;
    nothing.aggregation = false;
    nothing.labels_ply = false;
    const std::string scan = fresh("scene0016_00", nothing);
    ExpectInputError([&] { LoadScene(scan, SceneLoadOptions()); }, "no ground truth");
    SceneLoadOptions allow;
    allow.allow_missing = true;
    const world::Scene scene = LoadScene(scan, allow);  // the mesh alone: unannotated, on a floor quad
    EXPECT_EQ(scene.objects().size(), 2u);
  }
  {
    // Finite, rigid, but a kilometre-scale shift: the levelled scan is refused before anything grids it.
    ScanNetFixtureOptions no_aggregation;
    no_aggregation.aggregation = false;
    for (const char* id : {"scene0018_00", "scene0019_00"}) {
      const std::string scan = fresh(id, id == std::string("scene0018_00") ? ScanNetFixtureOptions() : no_aggregation);
      WriteText(scan + "/" + id + ".txt", "axisAlignment = 1 0 0 1e12 0 1 0 0 0 0 1 0 0 0 0 1\n");
      ExpectInputError([&] { LoadScene(scan, SceneLoadOptions()); }, "_vh_clean_2.ply: vertex coordinates beyond 10000 m");
    }
  }
  {
    const std::string scan = fresh("scene0017_00");
    WriteText(scan + "/scene0017_00_vh_clean_2.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\n");
    ExpectInputError([&] { LoadScene(scan, SceneLoadOptions()); }, "scene0017_00_vh_clean_2.ply");
  }
}

TEST(ScanNetTest, Nyu40NamesCoverTheFortyClasses) {
  EXPECT_EQ(Nyu40ClassName(1), "wall");
  EXPECT_EQ(Nyu40ClassName(2), "floor");
  EXPECT_EQ(Nyu40ClassName(22), "ceiling");
  EXPECT_EQ(Nyu40ClassName(32), "night stand");
  EXPECT_EQ(Nyu40ClassName(40), "otherprop");
  EXPECT_EQ(Nyu40ClassName(0), "");
  EXPECT_EQ(Nyu40ClassName(41), "");
}

}  // namespace
}  // namespace objscan::io
