#include "objscan/recognition/category_extent.h"

#include <cmath>

#include <gtest/gtest.h>

#include "objscan/recognition/model_database.h"
#include "objscan/recognition/test_database.h"

namespace objscan::recognition {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Eigen::Vector3f> BoxPoints(const Eigen::Vector3d& size_m, double yaw_rad, const Eigen::Vector3d& at_m) {
  std::vector<Eigen::Vector3f> points, normals;
  testing::BoxSurface(-0.5 * size_m, 0.5 * size_m, 0.02, &points, &normals);
  const Eigen::Matrix3f R = Eigen::AngleAxisf(static_cast<float>(yaw_rad), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  for (auto& p : points) p = R * p + at_m.cast<float>();
  return points;
}

TEST(MeasureExtentTest, AYawedBoxHasItsHeightAndFootprintDiagonal) {
  // 2 x 1 x 0.5 m turned by 30°: the world-axis box would be 2.23 x 1.87 m (diagonal 2.91 m); the
  // smallest rectangle is the box's own, diagonal sqrt(5) = 2.236 m, found to within the yaw step:
  // turned by d from it, a rectangle's diagonal is sqrt(D^2 + 2ab sin 2d) <= D sqrt(1 + sin 2d).
  const ObjectExtent e = MeasureExtent(BoxPoints({2.0, 1.0, 0.5}, 30.0 * kPi / 180.0, {3.0, -1.0, 0.25}));
  EXPECT_NEAR(e.height_m, 0.5, 1e-5);
  const double truth = std::sqrt(5.0);
  EXPECT_GE(e.footprint_diagonal_m, truth - 1e-4);
  EXPECT_LE(e.footprint_diagonal_m, truth * std::sqrt(1.0 + std::sin(kPi / 2.0 / 16.0)) + 1e-4);
}

TEST(MeasureExtentTest, ExactOnAStepAndZeroWhenEmpty) {
  const ObjectExtent e = MeasureExtent(BoxPoints({0.6, 0.8, 1.2}, 45.0 * kPi / 180.0, {0, 0, 0.6}), 16);
  EXPECT_NEAR(e.footprint_diagonal_m, 1.0, 1e-4);  // 45° is on the 16-step grid
  EXPECT_NEAR(e.height_m, 1.2, 1e-5);
  const ObjectExtent none = MeasureExtent({});
  EXPECT_EQ(none.height_m, 0.0);
  EXPECT_EQ(none.footprint_diagonal_m, 0.0);
}

TEST(MeasureExtentTest, TrimmingLeavesStrayPointsOut) {
  // A 0.6 x 0.8 x 1.2 m box (footprint diagonal 1.0 m, on the yaw grid) and a few stray points far
  // above and beside it, under 0.5% of the points: the extremes take the strays, the 1% quantiles not.
  std::vector<Eigen::Vector3f> points = BoxPoints({0.6, 0.8, 1.2}, 0.0, {0, 0, 0.6});
  const std::size_t n_box = points.size();
  const std::size_t n_stray = n_box / 400;
  ASSERT_GE(n_stray, 3u);
  for (std::size_t i = 0; i < n_stray; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(n_stray);
    points.emplace_back(-0.3f, -0.4f + 3.0f * t, 2.5f);  // a line along a wall, 1.3 m above the box
  }
  const ObjectExtent whole = MeasureExtent(points);
  EXPECT_NEAR(whole.height_m, 2.5, 1e-5);
  EXPECT_GT(whole.footprint_diagonal_m, 2.5);
  const ObjectExtent trimmed = MeasureExtent(points, 16, 0.01);
  EXPECT_NEAR(trimmed.height_m, 1.2, 0.03);
  EXPECT_NEAR(trimmed.footprint_diagonal_m, 1.0, 0.05);
  EXPECT_LE(trimmed.footprint_diagonal_m, 1.0 + 1e-4);
  // Trimming nothing is the whole extent; a trimmed range never exceeds the whole one.
  const ObjectExtent zero = MeasureExtent(points, 16, 0.0);
  EXPECT_EQ(zero.height_m, whole.height_m);
  EXPECT_EQ(zero.footprint_diagonal_m, whole.footprint_diagonal_m);
}

TEST(CategoryExtentsTest, RangesAreComponentWiseOverTheModels) {
  CategoryExtents extents;
  extents.Add(world::Category::kLamp, {0.4, 0.3});
  extents.Add(world::Category::kLamp, {1.8, 0.5});
  extents.Add(world::Category::kLamp, {1.0, 0.2});
  const ExtentRange* lamp = extents.Find(world::Category::kLamp);
  ASSERT_NE(lamp, nullptr);
  EXPECT_EQ(lamp->num_models, 3);
  EXPECT_DOUBLE_EQ(lamp->min.height_m, 0.4);
  EXPECT_DOUBLE_EQ(lamp->max.height_m, 1.8);
  EXPECT_DOUBLE_EQ(lamp->min.footprint_diagonal_m, 0.2);
  EXPECT_DOUBLE_EQ(lamp->max.footprint_diagonal_m, 0.5);
  EXPECT_EQ(extents.Find(world::Category::kBed), nullptr);
  EXPECT_EQ(extents.Find(world::Category::kWall), nullptr);  // structure has no models
}

TEST(CategoryExtentsTest, FromDatabaseMeasuresEachFullModel) {
  const ModelDatabase db = BuildDatabaseFromScans(testing::ShapeModels(0.02), testing::SmallDatabaseOptions());
  const CategoryExtents extents = CategoryExtents::FromDatabase(db);
  // The analytic table: top 1.2 x 0.8 m at 0.70-0.75 m on legs from the floor.
  const ExtentRange* table = extents.Find(world::Category::kTable);
  ASSERT_NE(table, nullptr);
  EXPECT_EQ(table->num_models, 1);
  EXPECT_NEAR(table->min.height_m, 0.75, 0.02);
  EXPECT_NEAR(table->min.footprint_diagonal_m, std::hypot(1.2, 0.8), 0.03);
  // The chair's back reaches 0.95 m.
  const ExtentRange* chair = extents.Find(world::Category::kChair);
  ASSERT_NE(chair, nullptr);
  EXPECT_NEAR(chair->max.height_m, 0.95, 0.02);
  EXPECT_EQ(extents.Find(world::Category::kBed), nullptr);
}

TEST(IsPlausibleExtentTest, BoundsAreRatiosOfTheSmallestAndLargestModel) {
  ExtentRange bed;
  bed.min = {0.6, 2.4};
  bed.max = {1.0, 2.5};
  bed.num_models = 4;
  SizePlausibilityOptions options;
  options.min_ratio = 0.5;
  options.max_ratio = 1.5;
  EXPECT_TRUE(IsPlausibleExtent({0.9, 2.5}, &bed, options));
  EXPECT_TRUE(IsPlausibleExtent({0.3, 1.2}, &bed, options));    // exactly at the lower bounds
  EXPECT_TRUE(IsPlausibleExtent({1.5, 3.75}, &bed, options));   // exactly at the upper bounds
  EXPECT_FALSE(IsPlausibleExtent({0.29, 2.5}, &bed, options));  // a slab of a bed
  EXPECT_FALSE(IsPlausibleExtent({0.9, 1.1}, &bed, options));   // a night stand's footprint
  EXPECT_FALSE(IsPlausibleExtent({1.51, 2.5}, &bed, options));
  EXPECT_FALSE(IsPlausibleExtent({0.9, 3.8}, &bed, options));   // a wall's length
  EXPECT_TRUE(IsPlausibleExtent({0.9, 1.1}, nullptr, options));  // no model: nothing to compare
}

TEST(SizePlausibilityOptionsTest, RejectsRatiosOnTheWrongSideOfOne) {
  SizePlausibilityOptions options;
  EXPECT_NO_THROW(options.Validate());
  options.min_ratio = 1.2;
  EXPECT_THROW(options.Validate(), ConfigError);
  options.min_ratio = 0.5;
  options.max_ratio = 0.9;
  EXPECT_THROW(options.Validate(), ConfigError);
}

}  // namespace
}  // namespace objscan::recognition
