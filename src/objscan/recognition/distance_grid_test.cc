#include "objscan/recognition/distance_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "objscan/common/rng.h"

namespace objscan::recognition {
namespace {

float BruteForceDistance(const std::vector<Eigen::Vector3f>& pts, const Eigen::Vector3f& q) {
  float best = std::numeric_limits<float>::infinity();
  for (const auto& p : pts) best = std::min(best, (p - q).norm());
  return best;
}

// The distance field is 1-Lipschitz, so interpolating exact vertex values is off by at most the
// distance to the farthest vertex of the cell (spacing * sqrt(3)), plus half a quantisation step.
TEST(DistanceGridTest, InterpolatesTheTruncatedDistanceWithinTheSpacing) {
  Rng rng(3);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 300; ++i) {  // a noisy sphere shell of radius 0.4 around (1, 2, 0.5)
    Eigen::Vector3f d(rng.Normal(0, 1), rng.Normal(0, 1), rng.Normal(0, 1));
    pts.push_back(Eigen::Vector3f(1.f, 2.f, 0.5f) + 0.4f * d.normalized());
  }
  const float truncation = 0.15f;
  const DistanceGrid grid(pts, truncation, 4096, 0.01f);
  ASSERT_FALSE(grid.empty());
  EXPECT_LE(grid.num_vertices(), 4096u);
  EXPECT_GE(grid.spacing_m(), 0.01f);
  const float tolerance = grid.spacing_m() * std::sqrt(3.f) + truncation / 255.f;
  double sum_error = 0.0;
  int n = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3f q(rng.Uniform(0.4, 1.6), rng.Uniform(1.4, 2.6), rng.Uniform(-0.1, 1.1));
    const float expected = std::min(truncation, BruteForceDistance(pts, q));
    const float got = grid.Distance(q);
    EXPECT_LE(got, truncation + 1e-6f);
    EXPECT_NEAR(got, expected, tolerance) << q.transpose();
    sum_error += std::abs(got - expected);
    ++n;
  }
  EXPECT_LT(sum_error / n, 0.5 * tolerance);  // typically far below the bound
  // On the points themselves the distance is small, far away it is the truncation.
  for (const auto& p : pts) EXPECT_LT(grid.Distance(p), tolerance);
  EXPECT_EQ(grid.Distance(Eigen::Vector3f(10.f, 10.f, 10.f)), truncation);
}

TEST(DistanceGridTest, EmptyInputGivesAnEmptyGrid) {
  EXPECT_TRUE(DistanceGrid({}, 0.1f, 1000, 0.01f).empty());
  EXPECT_TRUE(DistanceGrid({Eigen::Vector3f::Zero()}, 0.f, 1000, 0.01f).empty());
}

}  // namespace
}  // namespace objscan::recognition
