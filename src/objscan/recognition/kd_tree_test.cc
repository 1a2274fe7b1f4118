#include "objscan/recognition/kd_tree.h"

#include <gtest/gtest.h>

#include <limits>

#include "objscan/common/rng.h"

namespace objscan::recognition {
namespace {

int BruteNearest(const std::vector<Eigen::Vector3f>& pts, const Eigen::Vector3f& q, float* d2) {
  int best = -1;
  *d2 = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const float d = (pts[i] - q).squaredNorm();
    if (d < *d2) {
      *d2 = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

std::vector<Eigen::Vector3f> RandomPoints(int n, double extent, Rng* rng) {
  std::vector<Eigen::Vector3f> pts(n);
  for (auto& p : pts)
    p = Eigen::Vector3f(rng->Uniform(-extent, extent), rng->Uniform(-extent, extent), rng->Uniform(0.0, extent));
  return pts;
}

TEST(KdTreeTest, NearestMatchesBruteForceNearAndFar) {
  Rng rng(3);
  const std::vector<Eigen::Vector3f> pts = RandomPoints(700, 1.0, &rng);
  const KdTree3 tree(pts);
  for (double extent : {0.5, 5.0}) {  // queries inside the cloud and far outside it
    for (const auto& q : RandomPoints(300, extent, &rng)) {
      float d2 = 0.f, brute_d2 = 0.f;
      const int i = tree.Nearest(q, &d2);
      const int j = BruteNearest(pts, q, &brute_d2);
      EXPECT_FLOAT_EQ(d2, brute_d2);
      EXPECT_FLOAT_EQ((pts[i] - q).squaredNorm(), (pts[j] - q).squaredNorm());
    }
  }
}

class KdTreeWalkTest : public ::testing::TestWithParam<KdTree3::Walk> {};

TEST_P(KdTreeWalkTest, BoundedSearchFindsTheNearestInsideTheBoundOrKeepsTheHint) {
  const KdTree3::Walk walk = GetParam();
  Rng rng(5);
  const std::vector<Eigen::Vector3f> pts = RandomPoints(500, 1.0, &rng);
  const KdTree3 tree(pts);
  int closer = 0, kept = 0, none = 0;
  // Queries inside the cloud and up to 3 units outside it: kAuto takes both walks among them.
  for (const auto& q : RandomPoints(400, 4.0, &rng)) {
    float brute_d2 = 0.f;
    BruteNearest(pts, q, &brute_d2);
    // A hint: any point gives a valid bound; the result must be the exact nearest neighbour.
    const int hint = rng.UniformInt(0, static_cast<int>(pts.size()) - 1);
    const float hint_d2 = (pts[hint] - q).squaredNorm();
    float d2 = 0.f;
    const int i = tree.NearestBounded(q, hint_d2, hint, &d2, walk);
    EXPECT_FLOAT_EQ(d2, brute_d2);
    EXPECT_FLOAT_EQ((pts[i] - q).squaredNorm(), brute_d2);
    if (i == hint) {
      ++kept;
    } else {
      ++closer;
    }
    // A bare bound: -1 when nothing is strictly inside it.
    const float bound = 0.01f;
    const int b = tree.NearestBounded(q, bound, -1, &d2, walk);
    if (brute_d2 < 0.999f * bound) {
      EXPECT_FLOAT_EQ(d2, brute_d2);
      EXPECT_GE(b, 0);
    } else if (brute_d2 > 1.001f * bound) {
      EXPECT_EQ(b, -1);
      ++none;
    }
  }
  EXPECT_GT(closer, 0);
  EXPECT_GT(none, 0);
  (void)kept;
}

INSTANTIATE_TEST_SUITE_P(Walks, KdTreeWalkTest,
                         ::testing::Values(KdTree3::Walk::kAuto, KdTree3::Walk::kSplitPlanes, KdTree3::Walk::kBoxes));

TEST(KdTreeTest, EmptyTreeAndCoincidentPoints) {
  const KdTree3 empty;
  float d2 = 0.f;
  EXPECT_EQ(empty.Nearest(Eigen::Vector3f::Zero(), &d2), -1);
  EXPECT_EQ(empty.NearestBounded(Eigen::Vector3f::Zero(), 1.f, 7, &d2), 7);
  const KdTree3 same(std::vector<Eigen::Vector3f>(50, Eigen::Vector3f(1.f, 2.f, 3.f)));
  const int i = same.Nearest(Eigen::Vector3f::Zero(), &d2);
  EXPECT_GE(i, 0);
  EXPECT_FLOAT_EQ(d2, 14.f);
}

}  // namespace
}  // namespace objscan::recognition
