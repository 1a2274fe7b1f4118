#include "objscan/recognition/sweethome3d_sources.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "objscan/common/error.h"
#include "objscan/geometry/mesh.h"
#include "objscan/io/data_paths.h"
#include "objscan/io/sweethome3d.h"
#include "objscan/io/test_sweethome3d_fixture.h"

namespace objscan::recognition {
namespace {
namespace fs = std::filesystem;
using world::Category;

io::CategoryMap SweetHome3dMap() {
  return io::CategoryMap::Load(io::ResolveCategoryMapPath(kSweetHome3dCategoryMap));
}

std::optional<io::CategoryRuleMatch> MatchPiece(const io::CategoryMap& map, const std::string& name,
                                               const std::string& sh3d_category) {
  io::ModelIdentity identity;
  identity.name = name;
  identity.labels = {sh3d_category};
  return map.Match(identity);
}

// The category the map gives a piece; "skip" or "unmatched" otherwise.
std::string Mapped(const io::CategoryMap& map, const std::string& name, const std::string& sh3d_category) {
  const auto match = MatchPiece(map, name, sh3d_category);
  if (!match) return "unmatched";
  return match->skip ? "skip" : world::CategoryName(*match->category);
}

class TempFolder {
 public:
  TempFolder() {
    path_ = fs::temp_directory_path() /
            ("objscan_sh3d_sources_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string File(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

TEST(SweetHome3dSourcesTest, Specs) {
  EXPECT_TRUE(IsSweetHome3dSpec("sweethome3d"));
  EXPECT_TRUE(IsSweetHome3dSpec("a/b/Scopia.sh3f"));
  EXPECT_TRUE(IsSweetHome3dSpec("X.SH3F"));
  EXPECT_FALSE(IsSweetHome3dSpec("procedural"));
  EXPECT_FALSE(IsSweetHome3dSpec("room.world"));
  EXPECT_THROW(SweetHome3dCatalogsOf("/nonexistent/none.sh3f"), InputError);
}

TEST(SweetHome3dSourcesTest, FixtureCatalogBecomesSources) {
  TempFolder dir;
  const std::string path = dir.File("Test-Catalog.sh3f");
  io::testing::WriteSweetHome3dFixture(path);
  const SweetHome3dSources result = SweetHome3dModelSources({path}, SweetHome3dMap());
  ASSERT_EQ(result.sources.size(), 3u);
  ASSERT_EQ(result.skipped.size(), 1u);  // the sports car (Vehicles)
  EXPECT_NE(result.skipped[0].find("Test#car"), std::string::npos);
  EXPECT_TRUE(result.unmatched.empty());
  ASSERT_EQ(result.catalogs.size(), 1u);
  EXPECT_EQ(result.catalogs[0].pieces, 4);
  EXPECT_EQ(result.catalogs[0].models, 3);
  EXPECT_EQ(result.catalogs[0].name, "Test catalog");

  const ModelSource& bed = result.sources[0];
  EXPECT_EQ(bed.category, Category::kBed);
  EXPECT_EQ(bed.name, "bed/sh3d-test-catalog-bed-1");
  EXPECT_EQ(bed.source, "sweethome3d:" + fs::absolute(path).lexically_normal().string() + "#Test#bed 1");
  EXPECT_EQ(bed.support_heights_m, std::vector<float>{0.0f});
  EXPECT_EQ(bed.creator, "Alice");
  EXPECT_EQ(bed.license, "CC-BY 4.0 \xc2\xa9 Test Makers");
  EXPECT_EQ(result.sources[1].category, Category::kRefrigerator);
  EXPECT_EQ(result.sources[1].name, "refrigerator/sh3d-test-catalog-fridge");
  const ModelSource& cabinet = result.sources[2];
  EXPECT_EQ(cabinet.category, Category::kCabinet);
  ASSERT_EQ(cabinet.support_heights_m.size(), 1u);
  EXPECT_NEAR(cabinet.support_heights_m[0], 1.5f, 1e-6f);
  EXPECT_EQ(result.models_per_category.at("bed"), 1);

  // The loader of the source and LoadModelSourceMesh (from the stored source string) agree.
  const geometry::TriangleMesh loaded = bed.load_mesh();
  const geometry::Aabb3 box = geometry::Bounds(loaded);
  EXPECT_NEAR(box.Size().x(), 2.0, 1e-5);
  EXPECT_NEAR(box.Size().y(), 1.6, 1e-5);
  EXPECT_NEAR(box.Size().z(), 0.5, 1e-5);
  DatabaseModel model;
  model.category = bed.category;
  model.source = bed.source;
  const geometry::Aabb3 from_source = geometry::Bounds(LoadModelSourceMesh(model));
  EXPECT_NEAR(from_source.Size().x(), 2.0, 1e-5);
  EXPECT_NEAR(from_source.min_m.z(), 0.0, 1e-6);
  EXPECT_EQ(io::SweetHome3dSourceCatalog(bed.source), fs::absolute(path).lexically_normal().string());
  model.source = "sweethome3d:" + path + "#Test#nope";
  EXPECT_THROW(LoadModelSourceMesh(model), InputError);
}

// The map on names of Debian's catalogs (as written in their properties), one per kind of choice.
TEST(SweetHome3dSourcesTest, CategoryMapOnRealNames) {
  const io::CategoryMap map = SweetHome3dMap();
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"Armchair", "Living room", "chair"},          {"Winchester armchair", "Living room", "chair"},
      {"Corner sofa", "Living room", "sofa"},        {"Futon couch", "Living room", "sofa"},
      {"Opened convertible sofa BZ", "Bedroom", "bed"}, {"Convertible sofa BZ", "Bedroom", "sofa"},
      {"Bunk bed", "Bedroom", "bed"},                {"Bedside table", "Bedroom", "night_stand"},
      {"Dresser with drawers", "Living room", "dresser"}, {"Chest", "Bedroom", "cabinet"},
      {"Wardrobe", "Bedroom", "cabinet"},            {"Upper shelves cabinet", "Kitchen", "cabinet"},
      {"Island", "Kitchen", "cabinet"},              {"Island bath", "Bathroom", "bathtub"},
      {"Bath", "Bathroom", "bathtub"},               {"Shower stall", "Bathroom", "bathtub"},
      {"Shower curtain", "Bathroom", "curtain"},     {"Washbasin", "Bathroom", "sink"},
      {"Double vanity", "Bathroom", "sink"},         {"Toilets unit", "Bathroom", "toilet"},
      {"Toilet paper dispenser", "Bathroom", "other"}, {"TV", "Living room", "monitor"},
      {"Wall flat TV", "Living room", "monitor"},    {"TV stand", "Living room", "tv_stand"},
      {"Television cabinet", "Living room", "tv_stand"}, {"TV remote control", "Living room", "other"},
      {"Full bookcase", "Living room", "shelves"},   {"Vertical shelves", "Living room", "shelves"},
      {"Fridge", "Kitchen", "refrigerator"},         {"Bullet trash can", "Kitchen", "can"},
      {"Dustbin", "Office", "can"},                  {"Desk lamp", "Lights", "lamp"},
      {"Desk", "Office", "desk"},                    {"Coffee table", "Living room", "table"},
      {"Pool table", "Miscellaneous", "other"},      {"Bar stool", "Living room", "chair"},
      {"Wheelchair", "Miscellaneous", "other"},      {"Radio", "Miscellaneous", "radio"},
      {"Radiator", "Miscellaneous", "other"},        {"Double-hung window", "Doors and windows", "window"},
      {"Garage door", "Doors and windows", "door"},  {"Elevator", "Doors and windows", "skip"},
      {"Plant", "Living room", "other"},             {"Street lamp", "Lights", "skip"},
      {"Flashlight", "Lights", "other"},             {"Chair", "Exterior", "skip"},
      {"Sitting male", "Characters", "skip"},        {"VW new beetle", "Vehicles", "skip"},
      {"Spiral staircase", "Staircases", "skip"},    {"Iron railing", "Miscellaneous", "skip"},
  };
  for (const auto& [name, sh3d_category, expected] : cases) {
    EXPECT_EQ(Mapped(map, name, sh3d_category), expected) << name << " (" << sh3d_category << ")";
  }
}

// Debian's five catalogs: every piece is matched by a rule (mapped or skipped), every object category
// but curtain-free ones gets models. With $OBJSCAN_SH3D_MAPPING_OUT set, the mapping is written
// there (one "category | sh3d category | name | catalog: id" line per piece) for review.
TEST(SweetHome3dSourcesTest, RealDebianCatalogs) {
  const std::string dir = "/usr/share/sweethome3d/furniture";
  if (!fs::is_directory(dir)) {
    GTEST_SKIP() << "SKIPPED: " << dir << " missing (install Debian's sweethome3d-furniture package)";
  }
  const io::CategoryMap map = SweetHome3dMap();
  const std::vector<std::string> files = io::SweetHome3dCatalogFiles(dir);
  const SweetHome3dSources result = SweetHome3dModelSources(files, map);
  EXPECT_TRUE(result.unmatched.empty()) << result.unmatched.size() << " unmatched, first: " << result.unmatched.front();
  EXPECT_GT(result.sources.size(), 400u);
  for (const char* category : {"bed", "chair", "sofa", "table", "cabinet", "desk", "lamp", "shelves", "sink",
                               "toilet", "bathtub", "door", "window", "monitor", "refrigerator", "can", "other"}) {
    EXPECT_GT(result.models_per_category.count(category), 0u) << category;
  }
  if (const char* out_path = std::getenv("OBJSCAN_SH3D_MAPPING_OUT")) {
    std::ofstream out(out_path);
    for (const std::string& file : files) {
      const io::SweetHome3dCatalog catalog = io::LoadSweetHome3dCatalog(file);
      for (const auto& piece : catalog.pieces) {
        out << Mapped(map, piece.name, piece.category) << " | " << piece.category << " | " << piece.name << " | "
            << fs::path(file).stem().string() << ": " << piece.id << "\n";
      }
    }
    out << "# models per category:";
    for (const auto& [category, n] : result.models_per_category) out << " " << category << "=" << n;
    out << "; skipped " << result.skipped.size() << ", unmatched " << result.unmatched.size() << "\n";
  }
}

}  // namespace
}  // namespace objscan::recognition
