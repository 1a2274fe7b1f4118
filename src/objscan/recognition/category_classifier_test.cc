#include "objscan/recognition/category_classifier.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numeric>

#include "objscan/common/rng.h"
#include "objscan/recognition/test_shapes.h"

namespace objscan::recognition {
namespace {

// Feature indices (ShapeFeatures' layout).
constexpr int kLogHeight = 0, kLogLongSide = 1, kLogShortSide = 2, kFirstHeightBand = 5, kFirstSurfaceBand = 15,
              kVertical = 20, kSurfaceHeight = 21;

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
  for (int k = 0; k < kNumShapeFeatures; ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(f[k], raised[k], 0.02f);
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

TEST(CategoryClassifierTest, LearnsTwoKindsOfShapesAndNamesUnseenOnes) {
  Rng rng(11);
  std::vector<std::array<float, kNumShapeFeatures>> features;
  std::vector<world::Category> labels;
  for (int i = 0; i < 20; ++i) {
    features.push_back(RandomBox(true, &rng));
    labels.push_back(world::Category::kCabinet);
    features.push_back(RandomBox(false, &rng));
    labels.push_back(world::Category::kTable);
  }
  const CategoryClassifierOptions options;
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

TEST(CategoryClassifierTest, OptionsOutOfRangeNameTheirField) {
  CategoryClassifierOptions options;
  options.iterations = 0;
  try {
    options.Validate();
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("recognition.classifier.iterations"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace objscan::recognition
