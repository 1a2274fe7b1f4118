#include "objscan/planning/tdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace objscan::planning {
namespace {

LocalGrid CubeGrid(int n, double voxel_m) {
  LocalGrid g;
  g.nx = g.ny = g.nz = n;
  g.voxel_size_m = voxel_m;
  return g;
}

// 1-D kernel weight k of a sigma-1 Gaussian truncated at radius 3 and normalised.
double Weight1d(int k) {
  double sum = 0.0;
  for (int j = -3; j <= 3; ++j) sum += std::exp(-0.5 * j * j);
  return std::exp(-0.5 * k * k) / sum;
}

TEST(LocalGridTest, CoveringPadsAndCentres) {
  geometry::Aabb3 box;
  box.Extend(Eigen::Vector3d(0, 0, 0));
  box.Extend(Eigen::Vector3d(1.0, 0.5, 0.25));
  const LocalGrid g = LocalGrid::Covering(box, 0.05, 0.1, 1000000);
  EXPECT_EQ(g.nx, 24);  // (1.0 + 0.2) / 0.05
  EXPECT_EQ(g.ny, 14);
  EXPECT_EQ(g.nz, 9);
  EXPECT_DOUBLE_EQ(g.voxel_size_m, 0.05);
  int x, y, z;
  ASSERT_TRUE(g.VoxelOf(Eigen::Vector3f(0.0f, 0.0f, 0.0f), &x, &y, &z));
  EXPECT_EQ(x, 2);  // 0.1 m of padding = 2 voxels
  EXPECT_FALSE(g.VoxelOf(Eigen::Vector3f(-0.2f, 0.0f, 0.0f), &x, &y, &z));
  EXPECT_FALSE(g.VoxelOf(Eigen::Vector3f(NAN, 0.0f, 0.0f), &x, &y, &z));
  // Over budget: the voxel grows until the grid fits.
  const LocalGrid coarse = LocalGrid::Covering(box, 0.01, 0.1, 2000);
  EXPECT_LE(coarse.NumVoxels(), 2000u);
  EXPECT_GT(coarse.voxel_size_m, 0.01);
  EXPECT_GE(coarse.nx * coarse.voxel_size_m, 1.2 - 1e-9);
}

TEST(TdfTest, NoBlurIsTheIndicator) {
  const LocalGrid g = CubeGrid(5, 0.1);
  std::vector<float> f, scratch;
  BuildTdf(g, {Eigen::Vector3f(0.25f, 0.15f, 0.05f), Eigen::Vector3f(0.26f, 0.16f, 0.06f)}, 0.0, &f, &scratch);
  EXPECT_EQ(std::accumulate(f.begin(), f.end(), 0.0f), 1.0f);
  EXPECT_EQ(f[g.Index(2, 1, 0)], 1.0f);
}

TEST(TdfTest, BlurOfOneVoxelIsTheNormalisedKernel) {
  const LocalGrid g = CubeGrid(9, 0.1);
  std::vector<float> f, scratch;
  BuildTdf(g, {Eigen::Vector3f(0.45f, 0.45f, 0.45f)}, 1.0, &f, &scratch);
  EXPECT_NEAR(std::accumulate(f.begin(), f.end(), 0.0), 1.0, 1e-5);  // mass kept (kernel inside grid)
  EXPECT_NEAR(f[g.Index(4, 4, 4)], std::pow(Weight1d(0), 3), 1e-6);
  EXPECT_NEAR(f[g.Index(5, 4, 4)], Weight1d(1) * Weight1d(0) * Weight1d(0), 1e-6);
  EXPECT_NEAR(f[g.Index(3, 2, 5)], Weight1d(1) * Weight1d(2) * Weight1d(1), 1e-6);
  EXPECT_EQ(f[g.Index(0, 4, 4)], 0.0f);  // beyond the truncation radius of 3
  for (float v : f) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
  }
}

TEST(TdfTest, BlurOfAPlaneIsTheOneDimensionalProfile) {
  // A full z = 6 plane: inside the plane the blur is 1-D across it (far from the grid's side walls).
  const LocalGrid g = CubeGrid(13, 0.1);
  std::vector<Eigen::Vector3f> plane;
  for (int x = 0; x < 13; ++x)
    for (int y = 0; y < 13; ++y) plane.emplace_back(0.1f * x + 0.05f, 0.1f * y + 0.05f, 0.65f);
  std::vector<float> f, scratch;
  BuildTdf(g, plane, 1.0, &f, &scratch);
  for (int dz = -4; dz <= 4; ++dz) {
    const double expected = std::abs(dz) <= 3 ? Weight1d(dz) : 0.0;
    EXPECT_NEAR(f[g.Index(6, 6, 6 + dz)], expected, 1e-6) << dz;
  }
}

}  // namespace
}  // namespace objscan::planning
