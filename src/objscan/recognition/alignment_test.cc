#include "objscan/recognition/alignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "objscan/geometry/pose.h"
#include "objscan/recognition/keypoints.h"
#include "objscan/recognition/test_shapes.h"

namespace objscan::recognition {
namespace {

std::vector<Eigen::Vector3f> Keypoints(const std::vector<Eigen::Vector3f>& pts, std::uint64_t seed) {
  KeypointOptions options;
  Rng rng(seed);
  std::vector<Eigen::Vector3f> kp;
  for (int i : SampleKeypointsLloyd(pts, options, &rng)) kp.push_back(pts[i]);
  return kp;
}

// A yaw about z followed by a translation.
Eigen::Affine3d YawOffset(double yaw_rad, const Eigen::Vector3d& offset_m) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.rotate(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()));
  T.translation() = offset_m;
  return T;
}

std::vector<Eigen::Vector3f> Moved(const std::vector<Eigen::Vector3f>& points, const Eigen::Affine3d& T) {
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : points) out.push_back((T * p.cast<double>()).cast<float>());
  return out;
}

// Keypoints of an independent, coarser sampling of the chair's surface than the item's.
std::vector<Eigen::Vector3f> ResampledChairKeypoints() {
  std::vector<Eigen::Vector3f> resampled, normals;
  testing::ChairLike(0.013, &resampled, &normals);
  return Keypoints(resampled, 3);
}

// The query is the item moved by T_query_item; alignment must return its inverse.
void ExpectRecovers(const AlignmentResult& r, double yaw_rad, const Eigen::Vector3d& offset_m) {
  ASSERT_TRUE(r.ok());
  const Eigen::Affine3d T_query_item = YawOffset(yaw_rad, offset_m);
  const Eigen::Affine3d err = r.T_item_query * T_query_item;  // identity when exact
  const double angle_err = Eigen::AngleAxisd(err.linear()).angle();
  EXPECT_LT(geometry::RadToDeg(angle_err), 2.0);
  EXPECT_LT(err.translation().norm(), 0.01);
}

TEST(AlignmentTest, RecoversKnownYawAndOffsetOfAFullObject) {
  std::vector<Eigen::Vector3f> chair, normals;
  testing::ChairLike(0.01, &chair, &normals);
  const AlignmentTarget target(chair);
  AlignmentOptions options;
  for (double yaw_deg : {37.0, 143.0, -101.0}) {
    const double yaw = geometry::DegToRad(yaw_deg);
    const Eigen::Vector3d offset(1.7, -2.3, 0.05);
    // Query: an independent, coarser sampling of the same surface, moved.
    const std::vector<Eigen::Vector3f> query = Moved(ResampledChairKeypoints(), YawOffset(yaw, offset));
    SCOPED_TRACE(yaw_deg);
    ExpectRecovers(AlignToItem(query, target, options), yaw, offset);
  }
}

// With the item's distance grid scoring the initial hypotheses (as database entries have it), on
// keypoints as the database stores them; the grid is built once, on first use.
TEST(AlignmentTest, GridScoredInitialHypothesesRecoverKnownYawAndOffset) {
  std::vector<Eigen::Vector3f> chair, normals;
  testing::ChairLike(0.01, &chair, &normals);
  AlignmentTarget target(Keypoints(chair, 1));
  EXPECT_EQ(target.distance_grid(), nullptr);
  target.EnableDistanceGrid(0.15f, 16384, 0.025f);
  const DistanceGrid* grid = nullptr;
  std::thread other([&] { grid = target.distance_grid(); });
  const DistanceGrid* mine = target.distance_grid();
  other.join();
  ASSERT_NE(mine, nullptr);
  EXPECT_EQ(mine, grid);
  EXPECT_FALSE(mine->empty());
  const AlignmentOptions options;
  ASSERT_TRUE(options.grid_initial_scoring);
  for (double yaw_deg : {37.0, 143.0, -101.0}) {
    const double yaw = geometry::DegToRad(yaw_deg);
    const Eigen::Vector3d offset(1.7, -2.3, 0.05);
    const std::vector<Eigen::Vector3f> query = Moved(ResampledChairKeypoints(), YawOffset(yaw, offset));
    SCOPED_TRACE(yaw_deg);
    ExpectRecovers(AlignToItem(query, target, options), yaw, offset);
  }
}

TEST(AlignmentTest, RecoversKnownYawAndOffsetOfAPartialView) {
  std::vector<Eigen::Vector3f> chair, normals;
  testing::ChairLike(0.01, &chair, &normals);
  const AlignmentTarget target(chair);
  const double yaw = geometry::DegToRad(-58.0);
  const Eigen::Vector3d offset(-0.4, 0.9, 0.0);
  const Eigen::Affine3d T = YawOffset(yaw, offset);
  // Only what a camera at +x sees from the front: points with normals facing +x or up, x > -0.1.
  std::vector<Eigen::Vector3f> partial;
  for (std::size_t i = 0; i < chair.size(); ++i) {
    if (normals[i].x() > 0.5f || normals[i].z() > 0.5f || normals[i].y() < -0.5f) {
      partial.push_back((T * chair[i].cast<double>()).cast<float>());
    }
  }
  AlignmentOptions options;
  const AlignmentResult r = AlignToItem(Keypoints(partial, 5), target, options);
  ExpectRecovers(r, yaw, offset);
  EXPECT_GT(r.inlier_fraction, 0.95);
}

TEST(AlignmentTest, EstimatesAUniformScaleWhenAsked) {
  std::vector<Eigen::Vector3f> chair, normals;
  testing::ChairLike(0.01, &chair, &normals);
  const AlignmentTarget target(chair);
  std::vector<Eigen::Vector3f> query;
  for (const auto& p : Keypoints(chair, 8)) query.push_back(Eigen::Vector3f(1.1f * p) + Eigen::Vector3f(0.2f, 0.f, 0.f));
  AlignmentOptions options;
  options.estimate_scale = true;
  options.refine_points = 0;  // a scale is refined on all points (a subset leaves it biased)
  const AlignmentResult r = AlignToItem(query, target, options);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.scale, 1.0 / 1.1, 0.01);
  EXPECT_LT(r.trimmed_rms_m, 0.01);
}

TEST(AlignmentTest, CoarseThenRefineIsAlignToItemAndTruncationKeepsThePose) {
  std::vector<Eigen::Vector3f> chair, normals;
  testing::ChairLike(0.01, &chair, &normals);
  const AlignmentTarget target(chair);
  const double yaw = geometry::DegToRad(71.0);
  const Eigen::Vector3d offset(0.6, -1.2, 0.0);
  const std::vector<Eigen::Vector3f> query = Moved(Keypoints(chair, 4), YawOffset(yaw, offset));
  for (double truncation_m : {0.0, 0.15}) {
    AlignmentOptions options;
    options.initial_truncation_m = truncation_m;
    const std::vector<AlignmentHypothesis> coarse = CoarseAlign(query, target, options);
    ASSERT_EQ(static_cast<int>(coarse.size()), options.refine_hypotheses);
    EXPECT_LE(coarse[0].cost_m2, coarse[1].cost_m2);
    const AlignmentResult staged = RefineAlignment(query, target, coarse, options);
    const AlignmentResult whole = AlignToItem(query, target, options);
    EXPECT_TRUE(staged.T_item_query.isApprox(whole.T_item_query));
    SCOPED_TRACE(truncation_m);
    ExpectRecovers(staged, yaw, offset);
  }
  EXPECT_TRUE(RefineAlignment(query, target, {}, AlignmentOptions()).status == AlignmentStatus::kEmptyInput);
}

// The nearest grid gives the same correspondences as the kd-tree, so the same poses; stopping when
// the correspondences repeat skips only updates that would be the identity. The grid is built once,
// on first use, also when two threads reach it together.
TEST(AlignmentTest, GridCorrespondencesAndEarlyStopKeepThePose) {
  std::vector<Eigen::Vector3f> chair, normals;
  testing::ChairLike(0.01, &chair, &normals);
  const AlignmentTarget target(Keypoints(chair, 1));
  const NearestGrid* other_grid = nullptr;
  std::thread other([&] { other_grid = target.nearest_grid(); });
  const NearestGrid* grid = target.nearest_grid();
  other.join();
  ASSERT_NE(grid, nullptr);
  EXPECT_EQ(grid, other_grid);
  EXPECT_FALSE(grid->empty());
  EXPECT_LT(grid->memory_bytes(), 300u * 1024u);
  const std::vector<Eigen::Vector3f> resampled = ResampledChairKeypoints();
  for (double yaw_deg : {23.0, -131.0}) {
    const double yaw = geometry::DegToRad(yaw_deg);
    const Eigen::Vector3d offset(-0.8, 1.4, 0.02);
    const std::vector<Eigen::Vector3f> query = Moved(resampled, YawOffset(yaw, offset));
    SCOPED_TRACE(yaw_deg);
    AlignmentOptions kd_only;
    kd_only.grid_correspondences = false;
    kd_only.stop_when_correspondences_repeat = false;
    AlignmentOptions grid_only = kd_only;
    grid_only.grid_correspondences = true;
    const AlignmentOptions both;  // the defaults
    ASSERT_TRUE(both.grid_correspondences && both.stop_when_correspondences_repeat);
    const AlignmentResult a = AlignToItem(query, target, kd_only);
    const AlignmentResult b = AlignToItem(query, target, grid_only);
    const AlignmentResult c = AlignToItem(query, target, both);
    ExpectRecovers(a, yaw, offset);
    ExpectRecovers(b, yaw, offset);
    ExpectRecovers(c, yaw, offset);
    EXPECT_TRUE(b.T_item_query.isApprox(a.T_item_query, 1e-5));
    EXPECT_NEAR(b.inlier_fraction, a.inlier_fraction, 1e-9);
    EXPECT_NEAR(b.mean_squared_distance_m2, a.mean_squared_distance_m2, 1e-6 * a.mean_squared_distance_m2 + 1e-12);
    EXPECT_TRUE(c.T_item_query.isApprox(a.T_item_query, 1e-4));
    EXPECT_NEAR(c.trimmed_rms_m, a.trimmed_rms_m, 1e-4);
  }
}

TEST(AlignmentTest, StridedSubsetSpreadsOverAllPoints) {
  EXPECT_EQ(StridedSubset(10, 0).size(), 10u);
  EXPECT_EQ(StridedSubset(10, 20).size(), 10u);
  const std::vector<int> s = StridedSubset(10, 4);
  EXPECT_EQ(s, (std::vector<int>{0, 2, 5, 7}));
}

// Held on a floor, the item's z = 0 stays exactly at the floor's height while yaw and offset are
// recovered, also for a query whose lower part (the legs) was not seen.
TEST(AlignmentTest, HeldOnTheFloorTheItemStandsOnIt) {
  std::vector<Eigen::Vector3f> chair, normals;
  testing::ChairLike(0.01, &chair, &normals);
  const AlignmentTarget target(chair);
  const double floor_m = 0.3, yaw = geometry::DegToRad(61.0);
  const Eigen::Vector3d offset(-0.8, 1.4, floor_m);
  std::vector<Eigen::Vector3f> seat_and_back;
  for (const auto& p : Moved(ResampledChairKeypoints(), YawOffset(yaw, offset))) {
    if (p.z() > floor_m + 0.35) seat_and_back.push_back(p);
  }
  AlignmentConstraints on_floor;
  on_floor.floor_height_m = floor_m;
  const AlignmentResult r = AlignToItem(seat_and_back, target, AlignmentOptions(), on_floor);
  ExpectRecovers(r, yaw, offset);
  // p_item.z = p.z + t.z: the floor (query z = floor_m) is the item's z = 0.
  EXPECT_NEAR(r.T_item_query.translation().z(), -floor_m, 1e-9);
  for (const AlignmentHypothesis& h : CoarseAlign(seat_and_back, target, AlignmentOptions(), on_floor)) {
    EXPECT_NEAR(h.t.z(), -floor_m, 1e-9);
  }
}

// Free in z, ICP lifts a chair to a table's top; standing on the floor the chair cannot reach the top
// and fits the table far worse than a table does.
TEST(AlignmentTest, OnTheFloorAChairIsNotLiftedOntoATableTop) {
  std::vector<Eigen::Vector3f> chair, table, normals;
  testing::ChairLike(0.01, &chair, &normals);
  testing::TableLike(0.01, &table, &normals);
  const AlignmentTarget chair_target(Keypoints(chair, 1)), table_target(Keypoints(table, 1));
  std::vector<Eigen::Vector3f> table_top;  // what a camera above sees most of: the top, legs hidden
  for (const auto& p : Moved(Keypoints(table, 2), YawOffset(0.4, {2.0, 1.0, 0.0}))) {
    if (p.z() > 0.6) table_top.push_back(p);
  }
  AlignmentConstraints on_floor;
  on_floor.floor_height_m = 0.0;
  const AlignmentOptions options;
  const AlignmentResult chair_free = AlignToItem(table_top, chair_target, options);
  const AlignmentResult chair_held = AlignToItem(table_top, chair_target, options, on_floor);
  const AlignmentResult table_held = AlignToItem(table_top, table_target, options, on_floor);
  // Free, the chair's seat (z 0.40-0.46) is raised to the top (z 0.70-0.75).
  EXPECT_LT(chair_free.T_item_query.translation().z(), -0.15);
  EXPECT_NEAR(chair_held.T_item_query.translation().z(), 0.0, 1e-9);
  EXPECT_LT(table_held.mean_squared_distance_m2, 0.1 * chair_held.mean_squared_distance_m2);
}

TEST(AlignmentTest, EmptyInputIsAStatus) {
  const AlignmentTarget target(std::vector<Eigen::Vector3f>{{0, 0, 0}});
  EXPECT_EQ(AlignToItem({}, target, AlignmentOptions()).status, AlignmentStatus::kEmptyInput);
  EXPECT_EQ(AlignToItem({{0, 0, 0}}, AlignmentTarget(), AlignmentOptions()).status, AlignmentStatus::kEmptyInput);
}

}  // namespace
}  // namespace objscan::recognition
