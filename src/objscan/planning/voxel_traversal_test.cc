#include "objscan/planning/voxel_traversal.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace objscan::planning
