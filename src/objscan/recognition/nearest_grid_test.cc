#include "objscan/recognition/nearest_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "objscan/common/rng.h"

namespace objscan::recognition {
namespace {

float BruteForceNearest(const std::vector<Eigen::Vector3f>& pts, const Eigen::Vector3f& q) {
  float best = std::numeric_limits<float>::infinity();
  for (const auto& p : pts) best = std::min(best, (p - q).squaredNorm());
  return best;
}

// A noisy sphere shell (surface-like, as keypoints are) plus a few scattered points.
std::vector<Eigen::Vector3f> ShellPoints(int n, Rng* rng) {
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3f d(rng->Normal(0, 1), rng->Normal(0, 1), rng->Normal(0, 1));
    pts.push_back(Eigen::Vector3f(1.f, -2.f, 0.5f) + 0.4f * d.normalized() +
                  Eigen::Vector3f(rng->Normal(0, 0.01), rng->Normal(0, 0.01), rng->Normal(0, 0.01)));
  }
  for (int i = 0; i < n / 20; ++i)
    pts.push_back(Eigen::Vector3f(rng->Uniform(0.5, 1.5), rng->Uniform(-2.5, -1.5), rng->Uniform(0.0, 1.0)));
  return pts;
}

// Wherever the grid answers, it answers the exact nearest point; it must answer wherever the nearest
// point is within the band less a cell diagonal (that point then reaches the whole cell).
TEST(NearestGridTest, FindIsTheBruteForceNearestAndCoversTheBand) {
  Rng rng(7);
  const std::vector<Eigen::Vector3f> pts = ShellPoints(500, &rng);
  const float band = 0.2f;
  const NearestGrid grid(pts, band, 8192, 0.01f);
  ASSERT_FALSE(grid.empty());
  EXPECT_LE(grid.num_cells(), 8192u);
  EXPECT_GE(grid.cell_m(), 0.01f);
  const float must_cover = band - grid.cell_m() * std::sqrt(3.f);
  ASSERT_GT(must_cover, 0.f);
  int answered = 0, required = 0;
  for (int i = 0; i < 20000; ++i) {
    // Half near the points (as ICP correspondences are), half anywhere around them.
    const Eigen::Vector3f q =
        i % 2 == 0 ? Eigen::Vector3f(pts[rng.UniformInt(0, static_cast<int>(pts.size()) - 1)] +
                                     Eigen::Vector3f(rng.Normal(0, 0.05), rng.Normal(0, 0.05), rng.Normal(0, 0.05)))
                   : Eigen::Vector3f(rng.Uniform(0.3, 1.7), rng.Uniform(-2.7, -1.3), rng.Uniform(-0.2, 1.2));
    const float expected = BruteForceNearest(pts, q);
    float d2 = -1.f;
    const int found = grid.Find(q, &d2);
    if (std::sqrt(expected) <= must_cover) {
      ++required;
      ASSERT_GE(found, 0) << "uncovered query at distance " << std::sqrt(expected);
    }
    if (found < 0) continue;
    ++answered;
    ASSERT_LT(found, static_cast<int>(pts.size()));
    EXPECT_FLOAT_EQ(d2, (pts[found] - q).squaredNorm());
    ASSERT_NEAR(d2, expected, 1e-6f * (1.f + expected)) << "not the nearest point";
  }
  EXPECT_GT(required, 4000);  // the test exercises the band, not only far queries
  EXPECT_GE(answered, required);
}

TEST(NearestGridTest, CellRangeThenScanIsFindAndOutsideIsUncovered) {
  Rng rng(9);
  const std::vector<Eigen::Vector3f> pts = ShellPoints(200, &rng);
  const NearestGrid grid(pts, 0.1f, 4096, 0.02f);
  ASSERT_FALSE(grid.empty());
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3f q(rng.Uniform(0.4, 1.6), rng.Uniform(-2.6, -1.4), rng.Uniform(-0.1, 1.1));
    float d2_find = 0.f, d2_scan = 0.f;
    std::uint32_t begin = 0, end = 0;
    grid.CellRange(q, &begin, &end);
    const int scanned = grid.Scan(q, begin, end, &d2_scan);
    EXPECT_EQ(grid.Find(q, &d2_find), scanned);
    if (scanned >= 0) {
      EXPECT_EQ(d2_find, d2_scan);
    }
  }
  float d2 = 0.f;
  EXPECT_EQ(grid.Find(Eigen::Vector3f(10.f, 0.f, 0.f), &d2), -1);
  EXPECT_EQ(grid.Find(Eigen::Vector3f(std::numeric_limits<float>::quiet_NaN(), 0.f, 0.f), &d2), -1);
}

// Memory stays modest for a keypoint-sized set (a few hundred points): a cell lists ~2 candidates.
TEST(NearestGridTest, KeypointSizedSetStaysSmall) {
  Rng rng(11);
  const std::vector<Eigen::Vector3f> pts = ShellPoints(500, &rng);
  const NearestGrid grid(pts, 0.2f, 16384, 0.02f);
  ASSERT_FALSE(grid.empty());
  EXPECT_LT(grid.memory_bytes(), 300u * 1024u);
  EXPECT_LT(static_cast<double>(grid.num_candidates()) / grid.num_cells(), 6.0);
}

TEST(NearestGridTest, DegenerateInputsGiveAnEmptyGrid) {
  EXPECT_TRUE(NearestGrid({}, 0.1f, 1000, 0.01f).empty());
  EXPECT_TRUE(NearestGrid({{0, 0, 0}}, 0.f, 1000, 0.01f).empty());
  EXPECT_TRUE(NearestGrid({{0, 0, 0}}, 0.1f, 0, 0.01f).empty());
  const NearestGrid single({{1, 2, 3}}, 0.1f, 1000, 0.01f);
  ASSERT_FALSE(single.empty());
  float d2 = 0.f;
  EXPECT_EQ(single.Find(Eigen::Vector3f(1.f, 2.f, 3.02f), &d2), 0);
  EXPECT_NEAR(d2, 0.0004f, 1e-7f);
}

}  // namespace
}  // namespace objscan::recognition
