#include "objscan/recognition/database_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <limits>
#include <set>

#include "objscan/common/error.h"
#include "objscan/geometry/mesh_decimation.h"
#include "objscan/io/suncg_categories.h"
#include "objscan/recognition/recognizer.h"
#include "objscan/recognition/test_database.h"
#include "objscan/world/procedural/procedural.h"
#include "shared_data.h"

namespace objscan::recognition {
namespace {

namespace fs = std::filesystem;

// Fewer views and a small vocabulary keep these builds to seconds.
DatabaseBuildOptions FastOptions() {
  DatabaseBuildOptions options;
  options.scan.ring_elevations_deg = {20.0, 55.0};
  options.scan.ring_views = {6.0, 3.0};
  options.vocabulary.num_words = 32;
  options.vocabulary.max_training_descriptors = 5000;
  return options;
}

class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void WriteCubeObj(const fs::path& path, double size) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path);
  for (int i = 0; i < 8; ++i)
    out << "v " << size * (i & 1) << " " << size * ((i >> 1) & 1) << " " << size * ((i >> 2) & 1) << "\n";
  out << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
}

TEST(DatabaseBuilderTest, ProceduralModelsGiveFullModelsComponentsAndPairs) {
  std::vector<ModelSource> sources;
  for (const auto& s : ProceduralModelSources(1)) {
    if (s.category == world::Category::kChair || s.category == world::Category::kTable) sources.push_back(s);
  }
  ASSERT_EQ(sources.size(), 2u);
  const ModelDatabase db = BuildDatabase(sources, FastOptions());
  ASSERT_EQ(db.models().size(), 2u);
  for (std::size_t m = 0; m < 2; ++m) EXPECT_EQ(db.models()[m].support_heights_m, sources[m].support_heights_m);
  std::set<EntryKind> kinds;
  for (const auto& e : db.entries()) {
    kinds.insert(e.kind);
    const DatabaseModel& model = db.models()[e.model_index];
    EXPECT_EQ(e.category, model.category);
    EXPECT_FALSE(e.bow.empty());
    EXPECT_EQ(e.keypoint_normals.size(), e.keypoints.size());
    if (e.kind == EntryKind::kFullModel) {
      EXPECT_EQ(e.keypoints.size(), 500u);
      // Normalised: standing on the floor, centred in XY.
      EXPECT_NEAR(e.bounds.min_m.z(), 0.0, 0.03);
      EXPECT_NEAR(e.bounds.Center().x(), 0.0, 0.1);
      EXPECT_NEAR(e.bounds.Center().y(), 0.0, 0.1);
    } else {
      // Components and pairs are parts of their model's full scan.
      const DatabaseEntry& full = db.entries()[model.full_entry];
      // Components and pairs hold indices into it, not copies of its points.
      EXPECT_TRUE(e.points.empty());
      EXPECT_TRUE(e.normals.empty());
      const std::vector<Eigen::Vector3f> points = db.EntryPoints(static_cast<int>(&e - db.entries().data()));
      ASSERT_EQ(e.point_indices.size(), points.size());
      geometry::Aabb3 bounds;
      for (std::size_t k = 0; k < points.size(); ++k) {
        EXPECT_EQ(points[k], full.points[e.point_indices[k]]);
        bounds.Extend(points[k].cast<double>());
      }
      EXPECT_LT(points.size(), full.points.size());
      EXPECT_EQ(e.bounds.min_m, bounds.min_m);
      EXPECT_EQ(e.bounds.max_m, bounds.max_m);
    }
  }
  EXPECT_TRUE(kinds.count(EntryKind::kFullModel));
  EXPECT_TRUE(kinds.count(EntryKind::kComponent)) << "the chair and the table should split into parts";

  // A fresh single view of the chair model is recognized as the chair, placed on it.
  const Recognizer recognizer(db, RecognitionOptions());
  const geometry::TriangleMesh mesh = LoadModelSourceMesh(db.models()[0]);
  VirtualScanOptions scan = FastOptions().scan;
  Rng rng(3);
  const ModelScan view = ScanModel(mesh, {ViewFrom(geometry::Bounds(mesh), 0.7, 0.5, scan)}, scan, true, &rng);
  const auto similar = recognizer.Retrieve(recognizer.Describe(view.surface), RetrievalScope::kFullModels);
  ASSERT_FALSE(similar.empty());
  EXPECT_EQ(db.entries()[similar[0].entry].category, db.models()[0].category);
}

// Issue 48: every model's mesh comes back from the database alone. A world's object (source
// "<world>#<object>", which nothing can load), a mesh file deleted after the build and a generated
// model: each model's stored mesh is its normalised mesh within the triangle bound, its bounds those
// of the mesh the builder scanned within the decimation's grid.
TEST(DatabaseBuilderTest, EveryModelKeepsItsMeshWithoutItsSourceFiles) {
  TempDir dir("objscan_db_meshes");
  WriteCubeObj(dir.path() / "cabinet" / "cube.obj", 0.6);
  std::vector<ModelSource> sources = ModelSourcesFromFolder(dir.path().string(), nullptr);
  ASSERT_EQ(sources.size(), 1u);
  ModelSource ball;  // a fine sphere of ~40k triangles, as a world's object
  ball.category = world::Category::kLamp;
  ball.name = "lamp/ball";
  ball.source = (dir.path() / "gone.world").string() + "#ball_0";
  ball.load_mesh = [] {
    return geometry::Transformed(geometry::MakeSphere(0.25, 200), Eigen::Affine3d(Eigen::Translation3d(3.0, -1.0, 0.9)));
  };
  sources.push_back(ball);
  for (const auto& s : ProceduralModelSources(1)) {
    if (s.category == world::Category::kChair) sources.push_back(s);
  }
  ASSERT_EQ(sources.size(), 3u);
  DatabaseBuildOptions options = FastOptions();
  options.stored_mesh_max_triangles = 2000;
  const ModelDatabase built = BuildDatabase(sources, options);
  ASSERT_EQ(built.models().size(), 3u);
  const fs::path db_path = dir.path() / "meshes.db";
  built.Save(db_path.string());
  std::vector<geometry::TriangleMesh> scanned_meshes;  // what the builder scanned
  for (const auto& s : sources) scanned_meshes.push_back(NormalizeModel(s.load_mesh(), TypicalHeight(s.category)));
  fs::remove_all(dir.path() / "cabinet");  // the folder model's file is gone
  const ModelDatabase db = ModelDatabase::Load(db_path.string());
  ASSERT_EQ(db.models().size(), 3u);
  for (std::size_t m = 0; m < sources.size(); ++m) {
    const DatabaseModel& model = db.models()[m];
    SCOPED_TRACE(model.name);
    EXPECT_EQ(model.source, sources[m].source);  // kept for provenance
    const geometry::TriangleMesh& scanned = scanned_meshes[m];
    const geometry::BoundedMesh expected = geometry::DecimateToTriangleBudget(scanned, 2000, options.stored_mesh_min_cell_m);
    const geometry::TriangleMesh mesh = LoadModelSourceMesh(model);
    ASSERT_FALSE(mesh.Empty());
    EXPECT_LE(mesh.NumTriangles(), 2000u);
    EXPECT_EQ(mesh.vertices, expected.mesh.vertices);
    EXPECT_EQ(mesh.triangles, expected.mesh.triangles);
    // Within one grid cell of the scanned mesh's bounds (exact when it was small enough to keep).
    EXPECT_LE(expected.cell_m, 0.05);
    const double tolerance_m = std::max(expected.cell_m, 1e-6);
    const geometry::Aabb3 got = geometry::Bounds(mesh), want = geometry::Bounds(scanned);
    EXPECT_LT((got.min_m - want.min_m).cwiseAbs().maxCoeff(), tolerance_m);
    EXPECT_LT((got.max_m - want.max_m).cwiseAbs().maxCoeff(), tolerance_m);
  }
  EXPECT_EQ(db.models()[0].mesh.NumTriangles(), 12u);  // the cube as it was
  EXPECT_GT(db.models()[1].mesh.NumTriangles(), 1000u) << "the sphere on the finest grid that fits";
}

// A database built from scans has no meshes: LoadModelSourceMesh falls back to the source string and,
// when that cannot be loaded, says which model has no mesh.
TEST(DatabaseBuilderTest, ModelWithoutStoredMeshNorLoadableSourceIsNamed) {
  const ModelDatabase db = BuildDatabaseFromScans(testing::ShapeModels(0.02), testing::SmallDatabaseOptions());
  ASSERT_FALSE(db.models().empty());
  const DatabaseModel& model = db.models()[0];
  EXPECT_TRUE(model.mesh.Empty());
  try {
    LoadModelSourceMesh(model);
    ADD_FAILURE() << "loaded " << model.source;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("model " + model.name + ": no mesh in the database"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(model.source), std::string::npos) << e.what();
  }
  // With a procedural source, the generator makes it again.
  DatabaseModel generated = model;
  generated.category = ProceduralModelSources(1).front().category;
  generated.source = ProceduralModelSources(1).front().source;
  EXPECT_FALSE(LoadModelSourceMesh(generated).Empty());
}

// Where the generator stands its furniture: chairs, beds and doors on the floor, monitors on desks,
// dressers and stands, windows in the wall above it; every procedural model carries its category's
// heights into the database.
TEST(DatabaseBuilderTest, ProceduralSupportHeightsAreWhereTheGeneratorStandsFurniture) {
  using world::Category;
  const std::vector<std::vector<float>> heights = ProceduralSupportHeights();
  ASSERT_EQ(heights.size(), static_cast<std::size_t>(world::kNumCategories));
  const auto of = [&](Category c) -> const std::vector<float>& {
    return heights[static_cast<std::size_t>(world::CategoryId(c))];
  };
  for (Category c : {Category::kChair, Category::kBed, Category::kDoor, Category::kMonitor, Category::kWindow}) {
    SCOPED_TRACE(world::CategoryName(c));
    ASSERT_FALSE(of(c).empty());
    EXPECT_TRUE(std::is_sorted(of(c).begin(), of(c).end()));
  }
  for (Category c : {Category::kChair, Category::kBed, Category::kDoor}) {
    for (float h : of(c)) EXPECT_NEAR(h, 0.0, 0.02) << world::CategoryName(c);
  }
  for (float h : of(Category::kMonitor)) EXPECT_GT(h, 0.3);
  for (float h : of(Category::kWindow)) EXPECT_GT(h, 0.3);
  EXPECT_EQ(ProceduralSupportHeights(), heights);  // same rooms, same heights
  for (const ModelSource& s : ProceduralModelSources(1)) EXPECT_EQ(s.support_heights_m, of(s.category)) << s.name;
}

TEST(DatabaseBuilderTest, FolderListingFindsCategoriesAndModelNetLayout) {
  TempDir dir("objscan_models");
  WriteCubeObj(dir.path() / "chair" / "a.obj", 0.5);
  WriteCubeObj(dir.path() / "night_stand" / "train" / "b.obj", 0.5);
  WriteCubeObj(dir.path() / "night_stand" / "test" / "c.obj", 0.5);
  WriteCubeObj(dir.path() / "bookshelf" / "d.obj", 0.5);
  WriteCubeObj(dir.path() / "airplane" / "e.obj", 0.5);
  std::ofstream(dir.path() / "chair" / "notes.txt") << "not a mesh";
  std::vector<std::string> skipped;
  const auto sources = ModelSourcesFromFolder(dir.path().string(), &skipped);
  ASSERT_EQ(sources.size(), 4u);
  std::set<std::string> names;
  for (const auto& s : sources) names.insert(s.name);
  EXPECT_TRUE(names.count("chair/a"));
  EXPECT_TRUE(names.count("night_stand/train/b"));
  EXPECT_TRUE(names.count("night_stand/test/c"));
  EXPECT_TRUE(names.count("shelves/d"));  // alias
  ASSERT_EQ(skipped.size(), 1u);
  EXPECT_NE(skipped[0].find("airplane"), std::string::npos);
  EXPECT_FALSE(sources[0].load_mesh().Empty());

  TempDir empty("objscan_models_empty");
  EXPECT_THROW(ModelSourcesFromFolder(empty.path().string(), nullptr), InputError);
  EXPECT_THROW(ModelSourcesFromFolder((empty.path() / "missing").string(), nullptr), InputError);
}

TEST(DatabaseBuilderTest, NormalizeModelScalesUnitlessMeshesAndStandsThemOnTheFloor) {
  const geometry::TriangleMesh huge = geometry::MakeBox(Eigen::Vector3d(40, 30, 90));  // "centimetres"
  const geometry::Aabb3 b = geometry::Bounds(NormalizeModel(huge, 0.9));
  EXPECT_NEAR(b.Size().z(), 0.9, 1e-5);
  EXPECT_NEAR(b.min_m.z(), 0.0, 1e-5);
  EXPECT_NEAR(b.Center().x(), 0.0, 1e-5);
  const geometry::Aabb3 metric = geometry::Bounds(NormalizeModel(geometry::MakeBox(Eigen::Vector3d(0.5, 0.4, 0.9)), 2.0));
  EXPECT_NEAR(metric.Size().z(), 0.9, 1e-5);  // plausible metres are kept
}

// A database from the meshes of the OASC dev worlds (folder <category>/<id>.dae assembled with
// symlinks, categories from the SUNCG mapping and config/suncg_categories.csv) loads and answers.
TEST(DatabaseBuilderTest, OascDevMeshesBuildALoadableDatabaseThatAnswersQueries) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  const fs::path suncg = fs::path(data) / "oasc-dev" / "SUNCG";
  const io::SuncgModelMapping mapping = io::SuncgModelMapping::Load((suncg / "ModelCategoryMapping.csv").string());
  const io::SuncgCategoryTable table = io::SuncgCategoryTable::Load(io::ResolveConfigPath("suncg_categories.csv"));
  TempDir dir("objscan_oasc_models");
  // Up to two models of each of a few categories, in a deterministic order.
  std::vector<fs::path> model_dirs;
  for (const auto& e : fs::recursive_directory_iterator(suncg)) {
    if (e.is_regular_file() && e.path().extension() == ".dae" && e.path().stem() == e.path().parent_path().filename())
      model_dirs.push_back(e.path());
  }
  std::sort(model_dirs.begin(), model_dirs.end());
  std::map<world::Category, int> per_category;
  std::set<std::string> ids;
  int linked = 0;
  for (const fs::path& dae : model_dirs) {
    const std::string id = dae.stem().string();
    const io::SuncgClasses* classes = mapping.Lookup(id);
    if (!classes || ids.count(id)) continue;
    const auto category = table.Lookup(*classes);
    if (!category || world::IsStructural(*category) || *category == world::Category::kOther) continue;
    if (per_category[*category] >= 2 || (per_category.size() >= 4 && !per_category.count(*category))) continue;
    ++per_category[*category];
    ids.insert(id);
    const fs::path link = dir.path() / world::CategoryName(*category) / (id + ".dae");
    fs::create_directories(link.parent_path());
    fs::create_symlink(dae, link);
    ++linked;
  }
  ASSERT_GE(linked, 4) << "expected furniture meshes in " << suncg;
  std::vector<std::string> skipped;
  const auto sources = ModelSourcesFromFolder(dir.path().string(), &skipped);
  EXPECT_TRUE(skipped.empty());
  const ModelDatabase built = BuildDatabase(sources, FastOptions());
  const fs::path db_path = dir.path() / "oasc.db";
  built.Save(db_path.string());
  const ModelDatabase db = ModelDatabase::Load(db_path.string());
  ASSERT_EQ(db.models().size(), built.models().size());
  ASSERT_GE(db.models().size(), 4u);

  // A fresh view of one of the models finds that model's category among M(c), placed with a
  // plausible objectness.
  const Recognizer recognizer(db, RecognitionOptions());
  const DatabaseModel& model = db.models()[0];
  const geometry::TriangleMesh mesh = LoadModelSourceMesh(model);
  VirtualScanOptions scan = FastOptions().scan;
  Rng rng(5);
  const ModelScan view = ScanModel(mesh, {ViewFrom(geometry::Bounds(mesh), 0.4, 0.5, scan)}, scan, true, &rng);
  const auto similar = recognizer.Retrieve(recognizer.Describe(view.surface), RetrievalScope::kAllEntries);
  ASSERT_FALSE(similar.empty());
  bool found = false;
  for (const auto& m : similar) found = found || db.entries()[m.entry].category == model.category;
  EXPECT_TRUE(found) << model.name;
  EXPECT_GT(similar[0].objectness.objectness, 0.3);
}


// The style word of a generated model's name ("cabinet_filing_s7" -> "filing").
std::string StyleOf(const ModelSource& s) {
  const std::string prefix = std::string(world::CategoryName(s.category)) + "_";
  const std::string seed = s.source.substr(s.source.rfind('/') + 1);
  std::string name = world::procedural::GenerateFurniture(s.category, std::stoull(seed)).name.substr(prefix.size());
  return name.substr(0, name.find('_'));
}

std::vector<ModelSource> OfCategory(const std::vector<ModelSource>& all, world::Category category) {
  std::vector<ModelSource> out;
  for (const auto& s : all) {
    if (s.category == category) out.push_back(s);
  }
  return out;
}

TEST(GreedyMedoidsTest, PicksOneRowPerWellSeparatedClusterAndIsDeterministic) {
  // Three clusters on a line. Summed distances to all rows: 39.8 from 0.2, 40.0 from 10.1, so one
  // medoid is 0.2; then 10.1 (total 10.3 against 10.4 for 10.0), then 20.
  const std::vector<std::vector<double>> rows = {{0.0}, {10.0}, {0.1}, {20.0}, {0.2}, {10.1}};
  EXPECT_EQ(GreedyMedoids(rows, 1), (std::vector<int>{4}));
  EXPECT_EQ(GreedyMedoids(rows, 3), (std::vector<int>{3, 4, 5}));
  EXPECT_EQ(GreedyMedoids(rows, 3), GreedyMedoids(rows, 3));
  EXPECT_EQ(GreedyMedoids(rows, 9), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_TRUE(GreedyMedoids(rows, 0).empty());
}

TEST(ProceduralSamplingTest, StylesCoverEveryCabinetStyleTheFirstSeedsMiss) {
  const std::set<std::string> all_styles = {"kitchenbase", "pantry", "wardrobe", "sideboard", "display", "filing"};
  std::set<std::string> first, styles;
  for (const auto& s : OfCategory(ProceduralModelSources(8), world::Category::kCabinet)) first.insert(StyleOf(s));
  const auto stratified = OfCategory(ProceduralModelSources(8, 0, ProceduralSampling::kStyles), world::Category::kCabinet);
  ASSERT_EQ(stratified.size(), 8u);
  for (const auto& s : stratified) styles.insert(StyleOf(s));
  EXPECT_EQ(styles, all_styles);
  EXPECT_LT(first.size(), all_styles.size()) << "the case the stratified sampling is for";
  // Six styles in six slots: each exactly once.
  std::multiset<std::string> six;
  for (const auto& s : OfCategory(ProceduralModelSources(6, 0, ProceduralSampling::kStyles), world::Category::kCabinet)) {
    six.insert(StyleOf(s));
  }
  for (const auto& style : all_styles) EXPECT_EQ(six.count(style), 1u) << style;
  // Names stay unique and the same call gives the same models.
  std::set<std::string> names;
  const auto again = ProceduralModelSources(8, 0, ProceduralSampling::kStyles);
  const auto once = ProceduralModelSources(8, 0, ProceduralSampling::kStyles);
  ASSERT_EQ(again.size(), once.size());
  for (std::size_t i = 0; i < once.size(); ++i) {
    EXPECT_EQ(once[i].source, again[i].source);
    EXPECT_TRUE(names.insert(once[i].name).second) << once[i].name;
  }
}

TEST(ProceduralSamplingTest, SpreadCoversTheHeightRangeOfShelves) {
  const auto spread = OfCategory(ProceduralModelSources(8, 0, ProceduralSampling::kSpread), world::Category::kShelves);
  ASSERT_EQ(spread.size(), 8u);
  std::vector<double> heights;
  for (const auto& s : spread) {
    const geometry::Aabb3 box = geometry::Bounds(s.load_mesh());
    heights.push_back(box.max_m.z() - box.min_m.z());
  }
  // The first eight seeds hold no shelves between 0.96 m and 1.61 m tall, where most rooms' are.
  const auto mid = [](double h) { return h > 1.1 && h < 1.55; };
  EXPECT_TRUE(std::any_of(heights.begin(), heights.end(), mid));
  for (const auto& s : OfCategory(ProceduralModelSources(8), world::Category::kShelves)) {
    const geometry::Aabb3 box = geometry::Bounds(s.load_mesh());
    EXPECT_FALSE(mid(box.max_m.z() - box.min_m.z())) << "the case the spread sampling is for";
  }
}

TEST(ProceduralSamplingTest, StyleMedoidsKeepTheStyleCountsAndTakeEachStylesMiddle) {
  constexpr int kVariants = 8;
  const auto first = OfCategory(ProceduralModelSources(kVariants, 0, ProceduralSampling::kStyles), world::Category::kCabinet);
  const auto medoid =
      OfCategory(ProceduralModelSources(kVariants, 0, ProceduralSampling::kStyleMedoids), world::Category::kCabinet);
  ASSERT_EQ(medoid.size(), first.size());
  std::multiset<std::string> first_styles, medoid_styles;
  for (const auto& s : first) first_styles.insert(StyleOf(s));
  for (const auto& s : medoid) medoid_styles.insert(StyleOf(s));
  EXPECT_EQ(medoid_styles, first_styles);

  // Brute force: for a style drawn once, the chosen model is the pool member of that style with the
  // least summed distance to the style's others, sizes over their spread in the whole pool.
  struct Member { std::uint64_t index; std::string style; Eigen::Vector3d size; };
  std::vector<Member> pool;
  for (int k = 0; k < kVariants * kSamplingPoolPerVariant; ++k) {
    const auto model = world::procedural::GenerateFurniture(world::Category::kCabinet, world::procedural::DatabaseModelSeed(k));
    const geometry::Aabb3 box = geometry::Bounds(model.mesh);
    std::string name = model.name.substr(std::string("cabinet_").size());
    pool.push_back({static_cast<std::uint64_t>(k), name.substr(0, name.find('_')), box.max_m - box.min_m});
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero(), var = Eigen::Vector3d::Zero();
  for (const auto& m : pool) mean += m.size / pool.size();
  for (const auto& m : pool) var += (m.size - mean).cwiseAbs2() / pool.size();
  const Eigen::Vector3d sd = var.cwiseSqrt();
  int checked = 0;
  for (const std::string& style : std::set<std::string>(medoid_styles.begin(), medoid_styles.end())) {
    if (medoid_styles.count(style) != 1) continue;
    std::uint64_t best = 0;
    double best_cost = std::numeric_limits<double>::infinity();
    for (const auto& a : pool) {
      if (a.style != style) continue;
      double cost = 0.0;
      for (const auto& b : pool) {
        if (b.style == style) cost += (a.size - b.size).cwiseQuotient(sd).norm();
      }
      if (cost < best_cost - 1e-12) best_cost = cost, best = a.index;
    }
    for (const auto& s : medoid) {
      if (StyleOf(s) == style) {
        EXPECT_EQ(s.name, "cabinet/" + std::to_string(best)) << style;
      }
    }
    ++checked;
  }
  EXPECT_GE(checked, 4);
  // The case it is for: the first filing cabinet of the pool is 0.78 m tall, where the generator's
  // span 0.7-1.35 m; the medoid stands nearer their middle.
  for (const auto& s : medoid) {
    if (StyleOf(s) != "filing") continue;
    const geometry::Aabb3 box = geometry::Bounds(s.load_mesh());
    EXPECT_GT(box.max_m.z() - box.min_m.z(), 0.85);
  }
}

TEST(ProceduralSamplingTest, NamesParseAndUnknownOnesAreRejected) {
  for (ProceduralSampling s : {ProceduralSampling::kFirstSeeds, ProceduralSampling::kSpread, ProceduralSampling::kStyles,
                               ProceduralSampling::kStyleMedoids}) {
    EXPECT_EQ(ParseProceduralSampling(ProceduralSamplingName(s), "--sampling"), s);
  }
  try {
    ParseProceduralSampling("random", "--sampling");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--sampling"), std::string::npos);
  }
}

}  // namespace
}  // namespace objscan::recognition
