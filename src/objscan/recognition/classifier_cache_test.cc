#include "objscan/recognition/classifier_cache.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "objscan/common/error.h"
#include "objscan/io/test_util.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/recognition/model_database.h"
#include "objscan/recognition/test_database.h"
#include "objscan/recognition/test_shapes.h"

namespace objscan::recognition {
namespace {

// Probes: views of the analytic shapes the database holds, and a shape it does not.
struct ProbeSet {
  std::vector<Eigen::Vector3f> points, normals;
};
std::vector<ProbeSet> ProbeSets() {
  std::vector<ProbeSet> out;
  for (testing::ShapeFn shape : {&testing::ChairLike, &testing::TableLike, &testing::ShelfLike, &testing::SofaLike,
                                 &testing::CabinetLike}) {
    ProbeSet whole, front;
    shape(0.02, &whole.points, &whole.normals);
    for (std::size_t i = 0; i < whole.points.size(); ++i) {
      if (whole.normals[i].x() <= 0.1f) continue;
      front.points.push_back(whole.points[i]);
      front.normals.push_back(whole.normals[i]);
    }
    out.push_back(whole);
    out.push_back(front);
  }
  ProbeSet box;
  testing::BoxSurface({0.0, 0.0, 0.0}, {2.0, 0.3, 0.4}, 0.03, &box.points, &box.normals);
  out.push_back(box);
  return out;
}
std::vector<std::array<float, kNumShapeFeatures>> Probes() {
  std::vector<std::array<float, kNumShapeFeatures>> out;
  for (const ProbeSet& probe : ProbeSets()) out.push_back(ShapeFeatures(probe.points, probe.normals));
  return out;
}

const ModelDatabase& ShapeDatabase() {
  static const ModelDatabase db = BuildDatabaseFromScans(testing::ShapeModels(0.01), testing::SmallDatabaseOptions());
  return db;
}

CategoryClassifierOptions SmallOptions(const char* method) {
  CategoryClassifierOptions options;
  options.method = method;
  options.extra_training_databases = {};
  options.forest.num_trees = 8;
  options.forest.threads = 1;
  options.iterations = 50;
  options.network.point_features = 16;
  options.network.pooled_features = 32;
  options.network.head_features = 16;
  options.network.epochs = 2;
  options.network.threads = 1;
  return options;
}

class ClassifierFileTest : public ::testing::TestWithParam<const char*> {};

// What Load gives back answers every probe exactly as what was saved.
TEST_P(ClassifierFileTest, SavedAndLoadedClassifiesTheSame) {
  io::testing::TempDir dir;
  const CategoryClassifier trained = CategoryClassifier::Train(ShapeDatabase(), SmallOptions(GetParam()));
  ASSERT_TRUE(trained.trained());
  trained.Save(dir.File("c.bin"));
  const CategoryClassifier loaded = CategoryClassifier::Load(dir.File("c.bin"));
  EXPECT_EQ(loaded.classes(), trained.classes());
  EXPECT_EQ(loaded.max_depth(), trained.max_depth());
  EXPECT_EQ(loaded.has_network(), trained.has_network());
  for (const ProbeSet& probe : ProbeSets()) {
    EXPECT_EQ(loaded.Classify(probe.points, probe.normals), trained.Classify(probe.points, probe.normals));
  }
}

INSTANTIATE_TEST_SUITE_P(Learners, ClassifierFileTest, ::testing::Values("forest", "softmax", "network", "forest+network"));

TEST(ClassifierFileTest, UntrainedAndOneClassClassifiersRoundTrip) {
  io::testing::TempDir dir;
  CategoryClassifier().Save(dir.File("empty.bin"));
  EXPECT_FALSE(CategoryClassifier::Load(dir.File("empty.bin")).trained());
  const CategoryClassifier one =
      CategoryClassifier::Fit({ShapeFeatures({}, {})}, {world::Category::kChair}, SmallOptions("forest"));
  one.Save(dir.File("one.bin"));
  const CategoryClassifier loaded = CategoryClassifier::Load(dir.File("one.bin"));
  EXPECT_EQ(loaded.Classify(Probes()[0])[static_cast<std::size_t>(world::CategoryId(world::Category::kChair))], 1.0);
}

// A damaged file is refused with its path named, whatever part is damaged.
TEST(ClassifierFileTest, DamagedFilesAreRefusedNamingTheFile) {
  io::testing::TempDir dir;
  const std::string path = dir.File("c.bin");
  CategoryClassifier::Train(ShapeDatabase(), SmallOptions("forest")).Save(path);
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto write = [&](const std::string& b) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << b;
  };
  std::string flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x10;
  write(flipped);
  io::testing::ExpectInputError([&] { CategoryClassifier::Load(path); }, path + ": corrupt category classifier");
  write(bytes.substr(0, bytes.size() - 7));
  io::testing::ExpectInputError([&] { CategoryClassifier::Load(path); }, "truncated category classifier");
  write("OBJSCDB\n" + bytes.substr(8));
  io::testing::ExpectInputError([&] { CategoryClassifier::Load(path); }, "not an objscan category classifier");
  io::testing::ExpectInputError([&] { CategoryClassifier::Load(dir.File("missing.bin")); }, "missing.bin: cannot open");
}

// The key changes with anything that changes the trained classifier and with nothing else.
TEST(ClassifierCacheTest, KeyFollowsTheTrainingDataAndOptions) {
  const ModelDatabase& db = ShapeDatabase();
  const CategoryClassifierOptions options = SmallOptions("forest");
  const std::string key = ClassifierCacheKey({&db}, options);
  EXPECT_EQ(key.size(), 16u);
  CategoryClassifierOptions other = options;
  other.forest.threads = 4;
  other.cache = false;
  EXPECT_EQ(ClassifierCacheKey({&db}, other), key);
  other.network.threads = 3;
  EXPECT_EQ(ClassifierCacheKey({&db}, other), key);
  other.forest.seed = 2;
  EXPECT_NE(ClassifierCacheKey({&db}, other), key);
  other = options;
  other.network.epochs = 5;
  EXPECT_NE(ClassifierCacheKey({&db}, other), key);
  other = options;
  other.views_per_model = 12;
  EXPECT_NE(ClassifierCacheKey({&db}, other), key);
  ModelDatabase moved = BuildDatabaseFromScans(testing::ShapeModels(0.01), testing::SmallDatabaseOptions());
  EXPECT_EQ(ClassifierCacheKey({&moved}, options), key);
  moved.mutable_entries()[0].keypoints[0].x() += 1e-3f;
  EXPECT_NE(ClassifierCacheKey({&moved}, options), key);
  EXPECT_NE(ClassifierCacheKey({&db, &db}, options), key);
}

// First call trains and keeps the file; the second reads it and answers the same; a damaged file is
// trained again, said so, and replaced.
TEST(ClassifierCacheTest, TrainsOnceThenLoadsAndRepairsADamagedFile) {
  io::testing::TempDir dir;
  const std::string cache = dir.File("cache");  // created on first use
  const ModelDatabase& db = ShapeDatabase();
  const CategoryClassifierOptions options = SmallOptions("forest");
  CachedClassifierStatus status;
  const CategoryClassifier first = TrainOrLoadClassifier({&db}, options, cache, &status);
  EXPECT_FALSE(status.loaded);
  EXPECT_EQ(status.write_error, "");
  ASSERT_TRUE(std::filesystem::exists(status.path));
  const CategoryClassifier second = TrainOrLoadClassifier({&db}, options, cache, &status);
  EXPECT_TRUE(status.loaded);
  const CategoryClassifier direct = CategoryClassifier::Train(db, options);
  for (const auto& probe : Probes()) {
    EXPECT_EQ(second.Classify(probe), first.Classify(probe));
    EXPECT_EQ(second.Classify(probe), direct.Classify(probe));
  }
  std::filesystem::resize_file(status.path, 100);
  const CategoryClassifier repaired = TrainOrLoadClassifier({&db}, options, cache, &status);
  EXPECT_FALSE(status.loaded);
  EXPECT_NE(status.damage.find("truncated category classifier"), std::string::npos) << status.damage;
  EXPECT_EQ(repaired.Classify(Probes()[0]), direct.Classify(Probes()[0]));
  TrainOrLoadClassifier({&db}, options, cache, &status);
  EXPECT_TRUE(status.loaded);
}

TEST(ClassifierCacheTest, AnUnwritableCacheStillTrains) {
  io::testing::TempDir dir;
  io::testing::WriteText(dir.File("not-a-folder"), "x");
  const ModelDatabase& db = ShapeDatabase();
  CachedClassifierStatus status;
  const CategoryClassifier c = TrainOrLoadClassifier({&db}, SmallOptions("forest"), dir.File("not-a-folder"), &status);
  EXPECT_TRUE(c.trained());
  EXPECT_FALSE(status.loaded);
  EXPECT_NE(status.write_error, "");
}

}  // namespace
}  // namespace objscan::recognition
