#include "objscan/segmentation/segmentation_quality.h"

#include <gtest/gtest.h>

#include "objscan/common/rng.h"

namespace objscan::segmentation {
namespace {

double BruteForceRandIndex(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b) {
  std::int64_t agree = 0, pairs = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = i + 1; j < a.size(); ++j) {
      agree += ((a[i] == a[j]) == (b[i] == b[j])) ? 1 : 0;
      ++pairs;
    }
  }
  return pairs == 0 ? 1.0 : static_cast<double>(agree) / pairs;
}

TEST(SegmentationQualityTest, RandIndexMatchesBruteForcePairCounting) {
  Rng rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = rng.UniformInt(0, 60);
    const int ka = rng.UniformInt(1, 6), kb = rng.UniformInt(1, 6);
    std::vector<std::int32_t> a(n), b(n);
    for (int i = 0; i < n; ++i) {
      a[i] = rng.UniformInt(-1, ka);
      b[i] = rng.UniformInt(0, kb) * 1000;
    }
    EXPECT_DOUBLE_EQ(RandIndex(a, b), BruteForceRandIndex(a, b)) << "trial " << trial;
  }
}

TEST(SegmentationQualityTest, RandIndexKnownValues) {
  EXPECT_DOUBLE_EQ(RandIndex({1, 1, 2, 2}, {7, 7, 9, 9}), 1.0);  // same partition, other names
  // {1,1,1} vs {1,2,3}: all 3 pairs disagree.
  EXPECT_DOUBLE_EQ(RandIndex({1, 1, 1}, {1, 2, 3}), 0.0);
  EXPECT_THROW(RandIndex({1}, {1, 2}), std::invalid_argument);
}

TEST(SegmentationQualityTest, PurityKnownValues) {
  // Cluster 1: truth {5,5,6} -> 2; cluster 2: truth {6} -> 1; 3 of 4.
  EXPECT_DOUBLE_EQ(Purity({1, 1, 1, 2}, {5, 5, 6, 6}), 0.75);
  EXPECT_DOUBLE_EQ(Purity({}, {}), 1.0);
  // Over-segmentation is pure.
  EXPECT_DOUBLE_EQ(Purity({1, 2, 3, 4}, {5, 5, 6, 6}), 1.0);
}

}  // namespace
}  // namespace objscan::segmentation
