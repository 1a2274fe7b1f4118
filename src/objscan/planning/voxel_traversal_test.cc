#include "objscan/planning/voxel_traversal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include "objscan/common/rng.h"

namespace objscan::planning {
namespace {

using Cell = std::tuple<int, int, int>;

std::vector<Cell> Walk(int nx, int ny, int nz, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  std::vector<Cell> cells;
  for (VoxelWalker w(nx, ny, nz, a, b); !w.Done(); w.Next()) {
    EXPECT_EQ(w.index(), static_cast<std::size_t>(w.x() + nx * (w.y() + ny * w.z())));
    cells.emplace_back(w.x(), w.y(), w.z());
  }
  return cells;
}

TEST(VoxelWalkerTest, AxisAlignedRayFromOutside) {
  const std::vector<Cell> cells = Walk(10, 1, 1, {-5.0, 0.5, 0.5}, {20.0, 0.5, 0.5});
  ASSERT_EQ(cells.size(), 10u);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(cells[i], Cell(i, 0, 0));
  const std::vector<Cell> back = Walk(10, 1, 1, {7.5, 0.5, 0.5}, {2.5, 0.5, 0.5});
  ASSERT_EQ(back.size(), 6u);
  EXPECT_EQ(back.front(), Cell(7, 0, 0));
  EXPECT_EQ(back.back(), Cell(2, 0, 0));
}

TEST(VoxelWalkerTest, SegmentMissingTheGridVisitsNothing) {
  EXPECT_TRUE(Walk(4, 4, 4, {-1.0, -1.0, 0.5}, {-1.0, 10.0, 0.5}).empty());
  EXPECT_TRUE(Walk(4, 4, 4, {-3.0, 0.5, 0.5}, {-1.0, 0.5, 0.5}).empty());  // stops short of the grid
}

TEST(VoxelWalkerTest, MatchesDenseSamplingOnRandomSegments) {
  // Every voxel a dense sampling of the segment touches is walked, in order, and consecutive walked voxels
  // are face neighbours (the walk never skips).
  Rng rng(7);
  const int n = 12;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d a(rng.Uniform(-6, 18), rng.Uniform(-6, 18), rng.Uniform(-6, 18));
    const Eigen::Vector3d b(rng.Uniform(0, n), rng.Uniform(0, n), rng.Uniform(0, n));
    const std::vector<Cell> cells = Walk(n, n, n, a, b);
    std::vector<Cell> sampled;
    const int samples = 20000;
    for (int s = 0; s <= samples; ++s) {
      const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(s) / samples);
      const Cell c(static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y())),
                   static_cast<int>(std::floor(p.z())));
      if (std::get<0>(c) < 0 || std::get<1>(c) < 0 || std::get<2>(c) < 0 || std::get<0>(c) >= n ||
          std::get<1>(c) >= n || std::get<2>(c) >= n)
        continue;
      if (sampled.empty() || sampled.back() != c) sampled.push_back(c);
    }
    // Sampled voxels appear in the walk in the same order.
    std::size_t k = 0;
    for (const Cell& c : sampled) {
      while (k < cells.size() && cells[k] != c) ++k;
      ASSERT_LT(k, cells.size()) << "trial " << trial << " missed a voxel";
    }
    for (std::size_t i = 1; i < cells.size(); ++i) {
      const int d = std::abs(std::get<0>(cells[i]) - std::get<0>(cells[i - 1])) +
                    std::abs(std::get<1>(cells[i]) - std::get<1>(cells[i - 1])) +
                    std::abs(std::get<2>(cells[i]) - std::get<2>(cells[i - 1]));
      ASSERT_EQ(d, 1) << "trial " << trial;
    }
    // The walk ends in the voxel holding the end point.
    ASSERT_FALSE(cells.empty());
    EXPECT_EQ(cells.back(), Cell(static_cast<int>(std::floor(b.x())), static_cast<int>(std::floor(b.y())),
                                 static_cast<int>(std::floor(b.z()))));
  }
}

TEST(IsVoxelVisibleTest, BlockersBetweenCountOthersDoNot) {
  const int n = 10;
  std::vector<std::uint16_t> mask(n * n * n, 0);
  auto at = [&](int x, int y, int z) -> std::uint16_t& { return mask[x + n * (y + n * z)]; };
  const Eigen::Vector3d eye(-20.0, 5.5, 5.5);  // far outside, looking along +X
  at(8, 5, 5) = 1;                              // the target itself never blocks
  EXPECT_TRUE(IsVoxelVisible(n, n, n, mask.data(), 1, eye, 8, 5, 5, 1.5));
  at(9, 5, 5) = 1;  // behind the target
  EXPECT_TRUE(IsVoxelVisible(n, n, n, mask.data(), 1, eye, 8, 5, 5, 1.5));
  at(3, 5, 5) = 2;  // in between but of another bit
  EXPECT_TRUE(IsVoxelVisible(n, n, n, mask.data(), 1, eye, 8, 5, 5, 1.5));
  EXPECT_FALSE(IsVoxelVisible(n, n, n, mask.data(), 2, eye, 8, 5, 5, 1.5));
  EXPECT_FALSE(IsVoxelVisible(n, n, n, mask.data(), 3, eye, 8, 5, 5, 1.5));
  // The neighbour just in front is entered 1.5 voxels before the target centre: within a tolerance of
  // 1.6 voxels, not of 1.4.
  at(3, 5, 5) = 0;
  at(7, 5, 5) = 1;
  EXPECT_TRUE(IsVoxelVisible(n, n, n, mask.data(), 1, eye, 8, 5, 5, 1.6));
  EXPECT_FALSE(IsVoxelVisible(n, n, n, mask.data(), 1, eye, 8, 5, 5, 1.4));
  // A diagonal ray past a blocker that it does not cross.
  std::vector<std::uint16_t> empty(n * n * n, 0);
  empty[4 + n * (6 + n * 5)] = 1;  // (4, 6, 5): above the ray from (0.5, 0.5, 5.5) to (8.5, 5.5, 5.5)
  EXPECT_TRUE(IsVoxelVisible(n, n, n, empty.data(), 1, {0.5, 0.5, 5.5}, 8, 5, 5, 0.0));
  empty[5 + n * (3 + n * 5)] = 1;  // (5, 3, 5): on it (y = 0.5 + 5 * 4.5/8 = 3.3 at x = 5.5)
  EXPECT_FALSE(IsVoxelVisible(n, n, n, empty.data(), 1, {0.5, 0.5, 5.5}, 8, 5, 5, 0.0));
}

TEST(ChebyshevFreeDistanceTest, MatchesBruteForce) {
  Rng rng(11);
  const int nx = 9, ny = 7, nz = 6;
  std::vector<std::uint16_t> mask(nx * ny * nz, 0);
  for (int i = 0; i < 6; ++i) mask[rng.UniformInt(0, nx * ny * nz - 1)] = 1;
  std::vector<std::uint8_t> dist;
  ChebyshevFreeDistance(nx, ny, nz, mask.data(), &dist);
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x) {
        int best = 255;
        for (int i = 0; i < nx * ny * nz; ++i) {
          if (mask[i] == 0) continue;
          const int qx = i % nx, qy = (i / nx) % ny, qz = i / (nx * ny);
          best = std::min(best, std::max({std::abs(qx - x), std::abs(qy - y), std::abs(qz - z)}));
        }
        ASSERT_EQ(dist[x + nx * (y + ny * z)], best) << x << " " << y << " " << z;
      }
    }
  }
}

TEST(BlockingBitsTest, LeapingOverEmptySpaceGivesTheSameBitsAsTheWalk) {
  // Random sparse multi-bit occupancy; BlockingBits with and without the distance field, and a reference
  // that ORs the bits of VoxelWalker's voxels up to the same stopping rule.
  Rng rng(5);
  const int n = 24;
  std::vector<std::uint16_t> mask(n * n * n, 0);
  // Occupied voxels only in the middle, so that the box clipping matters.
  for (int i = 0; i < 150; ++i) {
    const int x = rng.UniformInt(4, 19), y = rng.UniformInt(4, 19), z = rng.UniformInt(4, 19);
    mask[x + n * (y + n * z)] |= static_cast<std::uint16_t>(1 << rng.UniformInt(0, 3));
  }
  std::vector<std::uint8_t> dist;
  ChebyshevFreeDistance(n, n, n, mask.data(), &dist);
  const VoxelOccupancy plain = VoxelOccupancy::Of(n, n, n, mask.data(), nullptr);
  const VoxelOccupancy leaping = VoxelOccupancy::Of(n, n, n, mask.data(), dist.data());
  int differing_from_zero = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Eigen::Vector3d eye(rng.Uniform(-30, 54), rng.Uniform(-30, 54), rng.Uniform(-30, 54));
    const int tx = rng.UniformInt(0, n - 1), ty = rng.UniformInt(0, n - 1), tz = rng.UniformInt(0, n - 1);
    const double tol = trial % 2 == 0 ? 1.5 : 0.0;
    const std::uint16_t stop_any = 1, stop_all = 0xE;
    const std::uint16_t walked = BlockingBits(plain, eye, tx, ty, tz, tol, stop_any, stop_all);
    const std::uint16_t leapt = BlockingBits(leaping, eye, tx, ty, tz, tol, stop_any, stop_all);
    ASSERT_EQ(walked, leapt) << "trial " << trial;
    const Eigen::Vector3d target(tx + 0.5, ty + 0.5, tz + 0.5);
    const double t_stop = 1.0 - tol / (target - eye).norm();
    std::uint16_t reference = 0;
    for (VoxelWalker w(n, n, n, eye, target); !w.Done(); w.Next()) {
      if (w.t_enter() >= t_stop || (w.x() == tx && w.y() == ty && w.z() == tz)) break;
      reference |= mask[w.index()];
      if ((reference & stop_any) || (reference & stop_all) == stop_all) break;
    }
    ASSERT_EQ(walked, reference) << "trial " << trial;
    differing_from_zero += walked != 0;
  }
  EXPECT_GT(differing_from_zero, 300);  // the rays do meet occupied voxels
}

}  // namespace
}  // namespace objscan::planning
