#include "objscan/common/union_find.h"

#include <gtest/gtest.h>

namespace objscan {
namespace {

TEST(UnionFindTest, UnionsAreTransitiveAndTheSmallestIndexIsTheRoot) {
  UnionFind sets(6);
  EXPECT_EQ(sets.Union(4, 2), 2);
  EXPECT_EQ(sets.Union(5, 4), 2);
  EXPECT_EQ(sets.Union(3, 1), 1);
  EXPECT_EQ(sets.Find(5), 2);
  EXPECT_EQ(sets.Find(3), 1);
  EXPECT_NE(sets.Find(5), sets.Find(3));
  // Joining two sets through non-root members makes the smaller root the parent.
  EXPECT_EQ(sets.Union(5, 3), 1);
  for (int i : {1, 2, 3, 4, 5}) EXPECT_EQ(sets.Find(i), 1) << i;
  EXPECT_EQ(sets.Find(0), 0);
  EXPECT_EQ(sets.Union(2, 2), 1);
}

}  // namespace
}  // namespace objscan
