#include "objscan/recognition/virtual_scan.h"

#include <gtest/gtest.h>

#include <cmath>

#include "objscan/common/rng.h"
#include "objscan/geometry/mesh.h"

namespace objscan::recognition {
namespace {

// A 1 m cube standing on the floor, seen level from +X without noise: the fused surface is the cube's
// +X face alone (x = 0.5 m, normals along +X), and a second scan gives the same points.
TEST(ScanSurfaceTest, SeesTheFaceTurnedToTheCameraAndNothingBehindIt) {
  const geometry::TriangleMesh cube = geometry::MakeBox(Eigen::Vector3d(-0.5, -0.5, 0.0), Eigen::Vector3d(0.5, 0.5, 1.0));
  VirtualScanOptions options;
  options.sensor.threads = 1;
  const geometry::Pose3 view = ViewFrom(geometry::Bounds(cube), 0.0, 0.0, options);
  const geometry::PointCloud surface = ScanSurface(cube, {view}, options, /*noise=*/false, nullptr);
  ASSERT_GT(surface.points.size(), 500u);
  ASSERT_TRUE(surface.HasNormals());
  for (std::size_t i = 0; i < surface.points.size(); ++i) {
    EXPECT_NEAR(surface.points[i].x(), 0.5f, 0.02f) << i;
    EXPECT_GT(surface.normals[i].x(), 0.9f) << i;
  }
  EXPECT_EQ(ScanSurface(cube, {view}, options, false, nullptr).points, surface.points);
}

// HalfOf keeps the points on one side of a vertical plane through the centroid: on a square grid in
// the XY plane, between a third and two thirds of them, those on the side the drawn direction points
// to; the same draw gives the same half, and an empty cloud stays empty.
TEST(HalfOfTest, KeepsOneSideOfAVerticalPlaneThroughTheCentroid) {
  geometry::PointCloud grid;
  for (int i = 0; i < 21; ++i) {
    for (int j = 0; j < 21; ++j) {
      grid.points.emplace_back(0.05f * i, 0.05f * j, 0.3f);
      grid.normals.emplace_back(0.f, 0.f, 1.f);
    }
  }
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    Rng rng(seed), again(seed);
    const geometry::PointCloud half = HalfOf(grid, &rng);
    EXPECT_EQ(half.points, HalfOf(grid, &again).points);
    ASSERT_EQ(half.normals.size(), half.points.size());
    EXPECT_GT(half.points.size(), grid.points.size() / 3);
    EXPECT_LT(half.points.size(), grid.points.size() * 2 / 3);
    // The plane's direction is the first draw (uniform angle); the half is exactly the grid's points
    // on its positive side of the centroid (0.5, 0.5).
    Rng probe(seed);
    const double angle = probe.Uniform(-M_PI, M_PI);
    const Eigen::Vector3f side(static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle)), 0.f);
    std::size_t expected = 0;
    for (const auto& p : grid.points) expected += (p - Eigen::Vector3f(0.5f, 0.5f, 0.3f)).dot(side) >= 0.f ? 1 : 0;
    EXPECT_NEAR(static_cast<double>(half.points.size()), static_cast<double>(expected), 2.0);
    for (const auto& p : half.points) EXPECT_GE((p - Eigen::Vector3f(0.5f, 0.5f, 0.3f)).dot(side), -1e-5f);
  }
  Rng rng(1);
  EXPECT_TRUE(HalfOf(geometry::PointCloud(), &rng).points.empty());
}

}  // namespace
}  // namespace objscan::recognition
