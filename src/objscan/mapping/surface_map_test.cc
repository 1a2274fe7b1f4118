#include "objscan/eval/ground_truth_votes.h"
#include "objscan/mapping/surface_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "objscan/mapping/testing/analytic_world.h"

namespace objscan::mapping {
namespace {

using testing::AnalyticWorld;
using testing::LookAt;

// Distance from p to the surface of the axis-aligned box [lo, hi] (p assumed near the surface).
double DistanceToBoxSurface(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const Eigen::Vector3d outside = (lo - p).cwiseMax(p - hi).cwiseMax(Eigen::Vector3d::Zero());
  if (outside.norm() > 0.0) return outside.norm();
  const Eigen::Vector3d inside = (p - lo).cwiseMin(hi - p);
  return inside.minCoeff();
}

TEST(SurfaceMapTest, BoxFusedFromEightNoisyViewsIsOneAccurateLayer) {
  const Eigen::Vector3d lo(-0.3, -0.2, 0.0), hi(0.3, 0.2, 0.5);
  AnalyticWorld world;
  world.Add(lo, hi, 1);
  Rng rng(7);
  SurfaceMap map;
  eval::GroundTruthVotes votes;
  for (int k = 0; k < 8; ++k) {
    const double yaw = 2.0 * M_PI * k / 8.0 + 0.2;
    const Eigen::Vector3d eye(1.6 * std::cos(yaw), 1.6 * std::sin(yaw), 1.2);
    const platform::DepthFrame frame = world.Render(LookAt(eye, Eigen::Vector3d(0, 0, 0.25)), &rng);
    FrameAssociation association;
    map.Integrate(frame, &association);
    votes.Observe(frame, association);
  }
  ASSERT_GT(map.size(), 10000u);

  std::size_t within_1cm = 0;
  double sum = 0.0;
  // Per face (axis, side) and lateral cell: how many elements sit in that column.
  std::map<std::tuple<int, int, int, int>, int> column_count;
  for (std::size_t i = 0; i < map.size(); ++i) {
    const Eigen::Vector3d p = map.position(i).cast<double>();
    const double d = DistanceToBoxSurface(p, lo, hi);
    sum += d;
    within_1cm += d <= 0.01 ? 1 : 0;
    EXPECT_EQ(votes.Instance(i), 1);
    const Eigen::Vector3f n = map.normal(i);
    int axis;
    n.cwiseAbs().maxCoeff(&axis);
    const int side = n[axis] > 0 ? 1 : -1;
    const geometry::VoxelKey k = geometry::KeyOf(map.position(i), 100.f);
    const int a = axis == 0 ? k.y : k.x;
    const int b = axis == 2 ? k.y : k.z;
    ++column_count[{axis, side, a, b}];
  }
  const double n = static_cast<double>(map.size());
  EXPECT_GE(within_1cm / n, 0.995) << "points within 1 cm of the true faces";
  EXPECT_LT(sum / n, 0.003) << "mean distance to the faces";
  // One layer: a face column holding more than one element is rare (cells on face borders and
  // box edges may hold two half-covered elements).
  std::size_t doubled = 0;
  for (const auto& kv : column_count) doubled += kv.second > 1 ? 1 : 0;
  EXPECT_LT(static_cast<double>(doubled) / column_count.size(), 0.03);
  // The visible faces (top + 4 sides) cover 0.24 + 2 * 0.3 + 2 * 0.2 m^2 = 1.24 m^2 = 12400 voxels.
  EXPECT_NEAR(n / 12400.0, 1.0, 0.12);
}

TEST(SurfaceMapTest, LabelsQueriesDirtySetAndRemove) {
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-0.5, -0.5, -0.05), Eigen::Vector3d(0.5, 0.5, 0.0), 1);
  SurfaceMap map;
  map.Integrate(world.Render(LookAt(Eigen::Vector3d(0.01, 0, 1.2), Eigen::Vector3d(0, 0, 0)), nullptr));
  ASSERT_GT(map.size(), 5000u);
  EXPECT_TRUE(map.Labels().empty());
  std::size_t left = 0;
  for (std::size_t i = 0; i < map.size(); ++i) {
    const bool is_left = map.position(i).x() < 0.f;
    left += is_left ? 1 : 0;
    map.SetLabel(i, is_left ? 3 : 5, 1.f);
  }
  EXPECT_EQ(map.Labels(), (std::vector<std::int32_t>{3, 5}));
  EXPECT_EQ(map.TakeDirtyLabels(), (std::vector<std::int32_t>{3, 5}));
  EXPECT_TRUE(map.TakeDirtyLabels().empty());
  EXPECT_EQ(map.Cloud(3).size(), left);
  EXPECT_EQ(map.Cloud(std::vector<std::int32_t>{3, 5}).size(), map.size());
  for (const auto& p : map.Cloud(3).points) EXPECT_LT(p.x(), 0.f);

  // Voting: one opposing vote of lower weight keeps the label; a stronger one flips it.
  map.VoteLabel(0, 9, 0.5f);
  EXPECT_EQ(map.label(0), map.position(0).x() < 0.f ? 3 : 5);
  map.VoteLabel(0, 9, 1.0f);
  EXPECT_EQ(map.label(0), 9);

  // Structural elements are not part of any label's cloud.
  map.SetStructure(1, Structure::kFloor);
  EXPECT_EQ(map.Cloud(std::vector<std::int32_t>{3, 5, 9}).size(), map.size() - 1);

  const std::size_t before = map.size();
  map.TakeDirtyLabels();
  EXPECT_EQ(map.Remove({3}), left - (map.label(0) == 9 && map.position(0).x() < 0.f ? 1 : 0));
  EXPECT_EQ(map.size(), before - (left - (map.position(0).x() < 0.f ? 1 : 0)));
  EXPECT_EQ(map.Labels(), (std::vector<std::int32_t>{5, 9}));
  EXPECT_EQ(map.TakeDirtyLabels(), (std::vector<std::int32_t>{3}));
  // The index still finds every remaining element.
  for (std::size_t i = 0; i < map.size(); ++i) EXPECT_EQ(map.Find(map.key(i)), static_cast<std::int32_t>(i));

  // Merging relabels.
  map.RelabelAll({9}, 5);
  EXPECT_EQ(map.Labels(), (std::vector<std::int32_t>{5}));
}

TEST(SurfaceMapTest, RepeatedViewsDoNotGrowTheMap) {
  AnalyticWorld world;
  world.Add(Eigen::Vector3d(-0.5, -0.5, -0.05), Eigen::Vector3d(0.5, 0.5, 0.0), 1);
  Rng rng(3);
  SurfaceMap map;
  const geometry::Pose3 T = LookAt(Eigen::Vector3d(0.7, 0.2, 1.5), Eigen::Vector3d(0, 0, 0));
  FrameAssociation assoc;
  map.Integrate(world.Render(T, &rng), &assoc);
  const std::size_t first = map.size();
  EXPECT_EQ(assoc.num_created, first);
  for (int k = 0; k < 5; ++k) map.Integrate(world.Render(T, &rng), &assoc);
  // Later frames of the same surface fuse into the existing layer.
  EXPECT_LT(static_cast<double>(map.size()), 1.05 * first);
  EXPECT_LT(static_cast<double>(assoc.num_created), 0.02 * assoc.num_fused);
  // Every fused pixel points at an element in range.
  for (std::int32_t e : assoc.pixel_element) EXPECT_LT(e, static_cast<std::int32_t>(map.size()));
}

TEST(SurfaceMapTest, RejectsMalformedFrame) {
  SurfaceMap map;
  platform::DepthFrame frame;
  frame.depth_m.resize(10);
  EXPECT_THROW(map.Integrate(frame), InputError);
  SurfaceMapOptions bad;
  bad.voxel_size_m = 0.0;
  EXPECT_THROW(bad.Validate(), ConfigError);
}

}  // namespace
}  // namespace objscan::mapping
