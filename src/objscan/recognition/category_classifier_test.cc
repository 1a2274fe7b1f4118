#include "objscan/recognition/category_classifier.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numeric>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/recognition/model_database.h"
#include "objscan/recognition/test_database.h"
#include "objscan/recognition/test_shapes.h"
#include "objscan/recognition/virtual_scan.h"

namespace objscan::recognition {
namespace {

// Feature indices (ShapeFeatures' layout).
constexpr int kLogHeight = 0, kLogLongSide = 1, kLogShortSide = 2, kFirstHeightBand = 5, kFirstSurfaceBand = 15,
              kVertical = 20, kSurfaceHeight = 21, kBottomAboveFloor = 26, kTopAboveFloor = 27,
              kFirstFloorSurfaceBand = 28, kFirstPairDistanceBand = 37;

std::vector<Eigen::Vector3f> Transformed(const std::vector<Eigen::Vector3f>& v, const Eigen::Affine3f& T, bool linear) {
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : v) out.push_back(linear ? Eigen::Vector3f(T.linear() * p) : Eigen::Vector3f(T * p));
  return out;
}

TEST(ShapeFeaturesTest, AreTheSameWhereverAndHoweverTurnedAboutZAShapeStands) {
  std::vector<Eigen::Vector3f> points, normals;
  testing::ChairLike(0.01, &points, &normals);
  const auto f = ShapeFeatures(points, normals);
  Eigen::Affine3f T = Eigen::Affine3f::Identity();
  T.translate(Eigen::Vector3f(3.0f, -2.0f, 0.0f));
  T.rotate(Eigen::AngleAxisf(0.65f, Eigen::Vector3f::UnitZ()));
  const auto g = ShapeFeatures(Transformed(points, T, false), Transformed(normals, T, true));
  for (int k = 0; k < kNumShapeFeatures; ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(f[k], g[k], 2e-3f);
  }
  // Raised: heights count from the shape's bottom. The chair's grid puts points on the bands' edges,
  // where rounding may move a few to the next band.
  const auto raised = ShapeFeatures(Transformed(points, Eigen::Affine3f(Eigen::Translation3f(0.f, 0.f, 0.7f)), false), normals);
  for (int k = 0; k < kNumRelativeShapeFeatures; ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(f[k], raised[k], 0.02f);
  }
  // ... and heights above the floor do not, unless the floor rises with it.
  EXPECT_NEAR(raised[kBottomAboveFloor], f[kBottomAboveFloor] + 0.7f, 0.02f);
  const auto raised_with_floor =
      ShapeFeatures(Transformed(points, Eigen::Affine3f(Eigen::Translation3f(0.f, 0.f, 0.7f)), false), normals, 0.7);
  for (int k = 0; k < kNumShapeFeatures; ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(f[k], raised_with_floor[k], 0.02f);
  }
}

// A box 1.0 x 0.5 x 0.8 m without its bottom, sampled evenly by area: its sides are vertical (2.4 of
// its 2.9 m2) and its top (0.5 m2) faces up 0.8 m above its bottom.
TEST(ShapeFeaturesTest, MeasureAKnownBox) {
  std::vector<Eigen::Vector3f> points, normals;
  testing::BoxSurface({0.0, 0.0, 0.0}, {1.0, 0.5, 0.8}, 0.01, &points, &normals);
  const auto f = ShapeFeatures(points, normals);
  // Extents run between the 2% and 98% quantiles: a little short of the box's.
  EXPECT_NEAR(std::exp(f[kLogHeight]) - 0.05, 0.8, 0.03);
  EXPECT_NEAR(std::exp(f[kLogLongSide]) - 0.05, 1.0, 0.05);
  EXPECT_NEAR(std::exp(f[kLogShortSide]) - 0.05, 0.5, 0.05);
  EXPECT_NEAR(f[kVertical], 2.4 / 2.9, 0.02);
  // The top lies in the band 0.6-0.9 m (index 2), and nothing else faces up or down.
  for (int b = 0; b < 5; ++b) EXPECT_NEAR(f[kFirstSurfaceBand + b], b == 2 ? 0.5 / 2.9 : 0.0, 0.02) << b;
  EXPECT_NEAR(f[kSurfaceHeight], 0.8, 0.03);
  // Standing on the floor; the top faces up in the floor band 0.7-0.85 m (index 4).
  EXPECT_NEAR(f[kBottomAboveFloor], 0.0, 0.03);
  EXPECT_NEAR(f[kTopAboveFloor], 0.8, 0.03);
  for (int b = 0; b < 9; ++b) EXPECT_NEAR(f[kFirstFloorSurfaceBand + b], b == 4 ? 0.5 / 2.9 : 0.0, 0.02) << b;
  // Pair distances: none beyond the box's diagonal (1.37 m), the histogram sums to 1.
  float pair_sum = 0.f;
  for (int b = 0; b < 10; ++b) pair_sum += f[kFirstPairDistanceBand + b];
  EXPECT_NEAR(pair_sum, 1.0f, 1e-4f);
  EXPECT_EQ(f[kFirstPairDistanceBand + 9], 0.f);  // >= 1.8 m
  // The height histogram sums to 1.
  float sum = 0.f;
  for (int b = 0; b < 10; ++b) sum += f[kFirstHeightBand + b];
  EXPECT_NEAR(sum, 1.0f, 1e-5f);
}

TEST(ShapeFeaturesTest, TooFewPointsGiveZeros) {
  const std::vector<Eigen::Vector3f> points(5, Eigen::Vector3f::Ones()), normals(5, Eigen::Vector3f::UnitZ());
  for (float v : ShapeFeatures(points, normals)) EXPECT_EQ(v, 0.f);
}

// Two kinds of random boxes: tall narrow ones (cabinets) and low wide ones (tables).
std::array<float, kNumShapeFeatures> RandomBox(bool tall, Rng* rng) {
  std::vector<Eigen::Vector3f> points, normals;
  const double w = tall ? rng->Uniform(0.4, 0.7) : rng->Uniform(1.0, 1.8);
  const double d = tall ? rng->Uniform(0.35, 0.6) : rng->Uniform(0.6, 0.9);
  const double h = tall ? rng->Uniform(1.5, 2.1) : rng->Uniform(0.65, 0.8);
  testing::BoxSurface({0.0, 0.0, 0.0}, {w, d, h}, 0.03, &points, &normals);
  return ShapeFeatures(points, normals);
}

class CategoryClassifierLearnerTest : public ::testing::TestWithParam<const char*> {};

TEST_P(CategoryClassifierLearnerTest, LearnsTwoKindsOfShapesAndNamesUnseenOnes) {
  Rng rng(11);
  std::vector<std::array<float, kNumShapeFeatures>> features;
  std::vector<world::Category> labels;
  for (int i = 0; i < 20; ++i) {
    features.push_back(RandomBox(true, &rng));
    labels.push_back(world::Category::kCabinet);
    features.push_back(RandomBox(false, &rng));
    labels.push_back(world::Category::kTable);
  }
  CategoryClassifierOptions options;
  options.method = GetParam();
  const CategoryClassifier classifier = CategoryClassifier::Fit(features, labels, options);
  ASSERT_TRUE(classifier.trained());
  EXPECT_EQ(classifier.classes().size(), 2u);
  for (int i = 0; i < 10; ++i) {
    const bool tall = i % 2 == 0;
    const auto p = classifier.Classify(RandomBox(tall, &rng));
    EXPECT_NEAR(std::accumulate(p.begin(), p.end(), 0.0), 1.0, 1e-9);
    EXPECT_EQ(p[world::CategoryId(world::Category::kChair)], 0.0);  // not in the training set
    EXPECT_GT(p[world::CategoryId(tall ? world::Category::kCabinet : world::Category::kTable)], 0.9) << i;
  }
  // Deterministic: the same data train the same classifier.
  const CategoryClassifier again = CategoryClassifier::Fit(features, labels, options);
  const auto probe = RandomBox(true, &rng);
  EXPECT_EQ(classifier.Classify(probe), again.Classify(probe));
}

INSTANTIATE_TEST_SUITE_P(Learners, CategoryClassifierLearnerTest, ::testing::Values("forest", "softmax"));

TEST(CategoryClassifierTest, OneCategoryIsAlwaysTheAnswerAndNoDataTrainsNothing) {
  Rng rng(3);
  const CategoryClassifier one =
      CategoryClassifier::Fit({RandomBox(true, &rng), RandomBox(false, &rng)},
                              {world::Category::kBed, world::Category::kBed}, CategoryClassifierOptions());
  ASSERT_TRUE(one.trained());
  EXPECT_DOUBLE_EQ(one.Classify(RandomBox(false, &rng))[world::CategoryId(world::Category::kBed)], 1.0);
  const CategoryClassifier none = CategoryClassifier::Fit({}, {}, CategoryClassifierOptions());
  EXPECT_FALSE(none.trained());
  for (double p : none.Classify(RandomBox(true, &rng))) EXPECT_EQ(p, 0.0);
  // Mismatched features and labels train nothing either.
  EXPECT_FALSE(CategoryClassifier::Fit({RandomBox(true, &rng)}, {}, CategoryClassifierOptions()).trained());
}

// Trained on a database of five analytic shapes (one model each), the recognizer names views of
// them it never saw (noisy surface points, from above at 30 degrees, every 45 degrees around)
// and halves of such views, and comes out the same at any thread count; whatever its learner.
class CategoryClassifierMethodTest : public ::testing::TestWithParam<const char*> {};

TEST_P(CategoryClassifierMethodTest, TrainedOnAShapeDatabaseNamesUnseenViewsAndHalves) {
  const ModelDatabase db = BuildDatabaseFromScans(testing::ShapeModels(0.01), testing::SmallDatabaseOptions());
  CategoryClassifierOptions options;
  options.method = GetParam();
  options.forest.num_trees = 24;
  options.forest.threads = 1;
  options.network.threads = 1;
  const CategoryClassifier classifier = CategoryClassifier::Train(db, options);
  ASSERT_TRUE(classifier.trained());
  EXPECT_EQ(classifier.has_network(), options.uses_network());
  options.forest.threads = 3;
  options.network.threads = 3;
  const CategoryClassifier threaded = CategoryClassifier::Train(db, options);
  const std::vector<std::pair<testing::ShapeFn, world::Category>> shapes = {
      {&testing::ChairLike, world::Category::kChair}, {&testing::TableLike, world::Category::kTable},
      {&testing::ShelfLike, world::Category::kShelves}, {&testing::SofaLike, world::Category::kSofa},
      {&testing::CabinetLike, world::Category::kCabinet}};
  Rng rng(17);
  int right = 0, half_right = 0, total = 0;
  for (const auto& [shape, category] : shapes) {
    std::vector<Eigen::Vector3f> points, normals;
    shape(0.02, &points, &normals);
    for (int v = 0; v < 8; ++v) {
      const double azimuth = M_PI / 4.0 * v + 0.2;
      const Eigen::Vector3f view(static_cast<float>(std::cos(azimuth) * std::cos(M_PI / 6)),
                                 static_cast<float>(std::sin(azimuth) * std::cos(M_PI / 6)),
                                 static_cast<float>(std::sin(M_PI / 6)));
      std::vector<Eigen::Vector3f> seen, seen_normals, half, half_normals;
      for (std::size_t i = 0; i < points.size(); ++i) {
        if (normals[i].dot(view) <= 0.1f) continue;
        seen.push_back(points[i] + Eigen::Vector3f(rng.Normal(0, 0.003), rng.Normal(0, 0.003), rng.Normal(0, 0.003)));
        seen_normals.push_back(normals[i]);
      }
      Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
      for (const auto& p : seen) centroid += p;
      centroid /= static_cast<float>(seen.size());
      const Eigen::Vector3f side(static_cast<float>(std::cos(azimuth + 1.0)), static_cast<float>(std::sin(azimuth + 1.0)), 0.f);
      for (std::size_t i = 0; i < seen.size(); ++i) {
        if ((seen[i] - centroid).dot(side) < 0.f) continue;
        half.push_back(seen[i]);
        half_normals.push_back(seen_normals[i]);
      }
      auto best = [](const CategoryClassifier::Probabilities& p) {
        return static_cast<world::Category>(std::max_element(p.begin(), p.end()) - p.begin());
      };
      const auto p = classifier.Classify(seen, seen_normals);
      EXPECT_EQ(p, threaded.Classify(seen, seen_normals));
      right += best(p) == category ? 1 : 0;
      half_right += best(classifier.Classify(half, half_normals)) == category ? 1 : 0;
      ++total;
    }
  }
  EXPECT_GE(right, total * 9 / 10) << right << " of " << total << " views";
  EXPECT_GE(half_right, total * 7 / 10) << half_right << " of " << total << " halves";
  if (classifier.has_network()) {  // the network needs the points, not only their features
    std::vector<Eigen::Vector3f> points_of_a_chair, normals_of_a_chair;
    testing::ChairLike(0.02, &points_of_a_chair, &normals_of_a_chair);
    EXPECT_THROW(classifier.Classify(ShapeFeatures(points_of_a_chair, normals_of_a_chair)), std::logic_error);
  }
}

INSTANTIATE_TEST_SUITE_P(Learners, CategoryClassifierMethodTest, ::testing::Values("forest", "network", "forest+network"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param) == "forest+network" ? std::string("forest_network")
                                                                               : std::string(info.param);
                         });

// The forest's depth is chosen by held-out validation. Two databases are two sources, each held out
// in turn: stumps (depth 1) cannot tell five shapes apart, depth 10 can, so 10 is chosen in either
// order. One database of one model per category has no category to hold out (forest.max_depth is
// kept), nor has a classifier without a list of depths.
TEST(CategoryClassifierTest, ChoosesTheForestDepthThatNamesHeldOutShapes) {
  const ModelDatabase db = BuildDatabaseFromScans(testing::ShapeModels(0.01), testing::SmallDatabaseOptions());
  CategoryClassifierOptions options;
  options.extra_training_databases = {};
  options.forest.num_trees = 8;
  options.forest.threads = 1;
  options.validation_trees = 4;
  options.forest.max_depth = 3;
  const std::vector<const ModelDatabase*> two_sources = {&db, &db};
  options.validation_depths = {1, 10};
  EXPECT_EQ(CategoryClassifier::Train(two_sources, options).max_depth(), 10);
  options.validation_depths = {10, 1};
  EXPECT_EQ(CategoryClassifier::Train(two_sources, options).max_depth(), 10);
  EXPECT_EQ(CategoryClassifier::Train(db, options).max_depth(), 3);
  options.validation_depths = {};
  EXPECT_EQ(CategoryClassifier::Train(two_sources, options).max_depth(), 3);
  options.method = "softmax";
  options.iterations = 20;
  EXPECT_EQ(CategoryClassifier::Train(db, options).max_depth(), 0);
  options.validation_depths = {2.5};
  try {
    options.Validate();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("recognition.classifier.validation_depths"), std::string::npos) << e.what();
  }
}

// training_views "rendered": the views of each model are rendered from its stored mesh by the live
// sensor (noise on). Trained on a chair, a bed and a table of the procedural generator, the classifier
// names noisy rendered views of them from azimuths it was not trained on, and it is the same at any
// thread count. A database built from scans stores no meshes: it trains as with "keypoints".
TEST(CategoryClassifierTest, RenderedTrainingViewsNameUnseenRenderedViews) {
  DatabaseBuildOptions build;
  build.scan.ring_elevations_deg = {20.0, 55.0};
  build.scan.ring_views = {6.0, 3.0};
  build.vocabulary.num_words = 32;
  build.vocabulary.max_training_descriptors = 5000;
  std::vector<ModelSource> sources;
  for (const ModelSource& s : ProceduralModelSources(1)) {
    if (s.category == world::Category::kChair || s.category == world::Category::kBed ||
        s.category == world::Category::kTable) {
      sources.push_back(s);
    }
  }
  ASSERT_EQ(sources.size(), 3u);
  const ModelDatabase db = BuildDatabase(sources, build);
  CategoryClassifierOptions options;
  options.extra_training_databases = {};
  options.training_views = "rendered";
  options.views_per_model = 6;
  options.half_views_per_model = 2;
  options.validation_depths = {};
  options.forest.num_trees = 16;
  options.forest.threads = 1;
  const CategoryClassifier classifier = CategoryClassifier::Train(db, options);
  ASSERT_TRUE(classifier.trained());
  options.forest.threads = 3;
  const CategoryClassifier threaded = CategoryClassifier::Train(db, options);

  VirtualScanOptions scan;
  scan.sensor.threads = 1;
  Rng rng(5);
  int right = 0, total = 0;
  for (const DatabaseModel& model : db.models()) {
    ASSERT_FALSE(model.mesh.triangles.empty()) << model.name;
    const geometry::Aabb3 bounds = geometry::Bounds(model.mesh);
    for (int v = 0; v < 4; ++v) {
      const double azimuth = M_PI / 2.0 * v + 0.4;  // between the training azimuths (every 60 degrees)
      const geometry::PointCloud surface = ScanSurface(model.mesh, {ViewFrom(bounds, azimuth, 0.5, scan)}, scan, true, &rng);
      ASSERT_TRUE(surface.HasNormals());
      const double floor_z = model.support_heights_m.empty() ? 0.0 : -model.support_heights_m.front();
      const auto p = classifier.Classify(surface.points, surface.normals, floor_z);
      EXPECT_EQ(p, threaded.Classify(surface.points, surface.normals, floor_z));
      right += static_cast<world::Category>(std::max_element(p.begin(), p.end()) - p.begin()) == model.category ? 1 : 0;
      ++total;
    }
  }
  EXPECT_GE(right, total - 1) << right << " of " << total << " rendered views";

  const ModelDatabase scanned = BuildDatabaseFromScans(testing::ShapeModels(0.01), testing::SmallDatabaseOptions());
  options.forest.threads = 1;
  CategoryClassifierOptions keypoint_options = options;
  keypoint_options.training_views = "keypoints";
  std::vector<Eigen::Vector3f> points, normals;
  testing::ChairLike(0.02, &points, &normals);
  EXPECT_EQ(CategoryClassifier::Train(scanned, options).Classify(points, normals),
            CategoryClassifier::Train(scanned, keypoint_options).Classify(points, normals));
}

TEST(CategoryClassifierTest, OptionsOutOfRangeNameTheirField) {
  CategoryClassifierOptions options;
  options.iterations = 0;
  try {
    options.Validate();
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("recognition.classifier.iterations"), std::string::npos) << e.what();
  }
  options = CategoryClassifierOptions();
  options.network.max_points = 2;
  try {
    options.Validate();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("recognition.classifier.network.max_points"), std::string::npos) << e.what();
  }
  std::vector<EncodedPointSet> no_sets;
  options = CategoryClassifierOptions();
  options.method = "network";
  Rng rng(1);
  EXPECT_THROW(CategoryClassifier::Fit({RandomBox(true, &rng)}, {world::Category::kBed}, options, {}, &no_sets),
               std::invalid_argument);
  options = CategoryClassifierOptions();
  options.method = "svm";
  EXPECT_THROW(options.Validate(), InputError);
  options = CategoryClassifierOptions();
  options.training_views = "photographs";
  try {
    options.Validate();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("recognition.classifier.training_views"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace objscan::recognition
