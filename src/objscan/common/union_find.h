#pragma once
// Disjoint sets over 0..n-1 (path halving). The smaller root becomes the parent, so roots (and
// orderings built on them) do not depend on the order of the unions' arguments.
#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

namespace objscan {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(static_cast<std::size_t>(n)) { std::iota(parent_.begin(), parent_.end(), 0); }
  int Find(int x) {
    while (parent_[static_cast<std::size_t>(x)] != x) {
      parent_[static_cast<std::size_t>(x)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(x)])];
      x = parent_[static_cast<std::size_t>(x)];
    }
    return x;
  }
  // Joins the sets of a and b; returns the root of the union.
  int Union(int a, int b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return a;
    if (b < a) std::swap(a, b);
    parent_[static_cast<std::size_t>(b)] = a;
    return a;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace objscan
