#include "objscan/recognition/kd_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace objscan::recognition {
namespace {
constexpr int kLeafSize = 12;

// Nodes BuildNode makes for n points (at most: coincident points stop a split early). A database
// holds ten thousand trees, so the node array is allocated once at its size, not grown by doubling.
std::size_t NodeCount(std::size_t n) {
  if (n <= static_cast<std::size_t>(kLeafSize)) return 1;
  return 1 + NodeCount(n / 2) + NodeCount(n - n / 2);
}
}  // namespace

void KdTree3::Build(const std::vector<Eigen::Vector3f>& points) {
  points_ = points;
  order_.resize(points_.size());
  std::iota(order_.begin(), order_.end(), 0);
  nodes_.clear();
  nodes_.reserve(points_.empty() ? 0 : NodeCount(points_.size()));
  if (!points_.empty()) BuildNode(0, static_cast<int>(points_.size()));
  ordered_.resize(points_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) ordered_[i] = points_[order_[i]];
  // NearestBounded's kAuto: a bound beyond half a leaf's typical diagonal crosses the split planes
  // of many cells, which only the boxes prune (BM_NearestBoundedFar: the two walks cost the same
  // near there, 10-20 cm for furniture-sized sets of 500-4000 points; boxes 2-10x faster beyond).
  double diagonal_sum = 0.0;
  int leaves = 0;
  for (const Node& n : nodes_) {
    if (n.dim >= 0) continue;
    const float dx = n.hi[0] - n.lo[0], dy = n.hi[1] - n.lo[1], dz = n.hi[2] - n.lo[2];
    diagonal_sum += std::sqrt(dx * dx + dy * dy + dz * dz);
    ++leaves;
  }
  const double half_leaf = leaves > 0 ? 0.5 * diagonal_sum / leaves : 0.0;
  split_planes_max_d2_ = static_cast<float>(half_leaf * half_leaf);
}

int KdTree3::BuildNode(int begin, int end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  nodes_[id].a = begin;
  nodes_[id].b = end;
  Eigen::Vector3f lo = points_[order_[begin]], hi = lo;
  for (int i = begin + 1; i < end; ++i) {
    lo = lo.cwiseMin(points_[order_[i]]);
    hi = hi.cwiseMax(points_[order_[i]]);
  }
  for (int d = 0; d < 3; ++d) {
    nodes_[id].lo[d] = lo[d];
    nodes_[id].hi[d] = hi[d];
  }
  if (end - begin <= kLeafSize) return id;
  int dim = 0;
  (hi - lo).maxCoeff(&dim);
  if (hi[dim] <= lo[dim]) return id;  // all points coincide: keep a leaf
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](int a, int b) { return points_[a][dim] < points_[b][dim]; });
  const float split = points_[order_[mid]][dim];
  BuildNode(begin, mid);  // preorder: the left child is id + 1
  const int right = BuildNode(mid, end);
  Node& n = nodes_[id];
  n.dim = dim;
  n.split = split;
  n.a = right;
  n.b = 0;
  return id;
}

void KdTree3::SearchNear(const Eigen::Vector3f& q, int* best, float* best_d2) const {
  // Depth-first, near side first, with an explicit stack of (node, squared distance to its slab):
  // the cheapest walk when a good bound (a hint) prunes most of the tree anyway. Median splits keep
  // the depth below 32 for any int-sized point count.
  struct Pending {
    std::int32_t node;
    float bound_d2;
  };
  Pending stack[64];
  int top = 0;
  stack[top++] = {0, 0.f};
  const Node* nodes = nodes_.data();
  const Eigen::Vector3f* pts = ordered_.data();
  while (top > 0) {
    const Pending p = stack[--top];
    if (p.bound_d2 >= *best_d2) continue;
    int id = p.node;
    // Walk down to the leaf on q's side, deferring the far children.
    while (nodes[id].dim >= 0) {
      const Node& n = nodes[id];
      const float diff = q[n.dim] - n.split;
      const int near = diff < 0.f ? id + 1 : n.a;
      const int far = diff < 0.f ? n.a : id + 1;
      const float far_d2 = diff * diff;
      if (far_d2 < *best_d2) stack[top++] = {far, far_d2};
      id = near;
    }
    const Node& leaf = nodes[id];
    for (int i = leaf.a; i < leaf.b; ++i) {
      const float dx = pts[i].x() - q.x(), dy = pts[i].y() - q.y(), dz = pts[i].z() - q.z();
      const float d2 = dx * dx + dy * dy + dz * dz;
      if (d2 < *best_d2) {
        *best_d2 = d2;
        *best = i;
      }
    }
  }
}

void KdTree3::Search(const Eigen::Vector3f& q, int* best, float* best_d2) const {
  // Depth-first, nearer child first (by the squared distance to the children's bounds), with an
  // explicit stack of the deferred children and their distances. Median splits keep the depth below
  // 32 for any int-sized point count.
  struct Pending {
    std::int32_t node;
    float d2;
  };
  Pending stack[64];
  int top = 0;
  const Node* nodes = nodes_.data();
  const Eigen::Vector3f* pts = ordered_.data();
  const float qx = q.x(), qy = q.y(), qz = q.z();
  stack[top++] = {0, BoxDistance2(nodes[0], qx, qy, qz)};
  float bd2 = *best_d2;
  int bi = *best;
  while (top > 0) {
    const Pending p = stack[--top];
    if (p.d2 >= bd2) continue;
    int id = p.node;
    // Walk down to a leaf, always into the nearer child, deferring the other when it may matter.
    bool pruned = false;
    while (nodes[id].dim >= 0) {
      const int left = id + 1, right = nodes[id].a;
      const float dl = BoxDistance2(nodes[left], qx, qy, qz);
      const float dr = BoxDistance2(nodes[right], qx, qy, qz);
      const bool left_first = dl < dr || (dl == dr && q[nodes[id].dim] < nodes[id].split);
      const int near = left_first ? left : right, far = left_first ? right : left;
      const float near_d2 = left_first ? dl : dr, far_d2 = left_first ? dr : dl;
      if (far_d2 < bd2) stack[top++] = {far, far_d2};
      if (near_d2 >= bd2) {
        pruned = true;
        break;
      }
      id = near;
    }
    if (pruned) continue;
    const Node& leaf = nodes[id];
    for (int i = leaf.a; i < leaf.b; ++i) {
      const float dx = pts[i].x() - qx, dy = pts[i].y() - qy, dz = pts[i].z() - qz;
      const float d2 = dx * dx + dy * dy + dz * dz;
      if (d2 < bd2) {
        bd2 = d2;
        bi = i;
      }
    }
  }
  *best_d2 = bd2;
  *best = bi;
}

int KdTree3::Nearest(const Eigen::Vector3f& q, float* squared_distance) const {
  if (points_.empty()) {
    if (squared_distance) *squared_distance = std::numeric_limits<float>::infinity();
    return -1;
  }
  int best = -1;
  float best_d2 = std::numeric_limits<float>::infinity();
  Search(q, &best, &best_d2);
  if (best < 0) {  // only for non-finite queries: fall back to the first point
    best = 0;
    best_d2 = (ordered_[0] - q).squaredNorm();
  }
  if (squared_distance) *squared_distance = best_d2;
  return order_[best];
}

int KdTree3::NearestBounded(const Eigen::Vector3f& q, float bound_d2, int hint, float* squared_distance,
                            Walk walk) const {
  int best = -1;
  float best_d2 = bound_d2;
  if (walk == Walk::kAuto) walk = bound_d2 > split_planes_max_d2_ ? Walk::kBoxes : Walk::kSplitPlanes;
  if (!points_.empty()) {
    if (walk == Walk::kBoxes) {
      Search(q, &best, &best_d2);
    } else {
      SearchNear(q, &best, &best_d2);
    }
  }
  if (best < 0) {
    if (squared_distance) *squared_distance = hint >= 0 ? bound_d2 : std::numeric_limits<float>::infinity();
    return hint;
  }
  if (squared_distance) *squared_distance = best_d2;
  return order_[best];
}

void KdTree3::KNearest(const Eigen::Vector3f& q, int k, std::vector<int>* indices,
                       std::vector<float>* squared_distances) const {
  indices->clear();
  if (squared_distances) squared_distances->clear();
  if (points_.empty() || k <= 0) return;
  // Max-heap of (d2, ordered index) holding the k best so far.
  std::vector<std::pair<float, int>> heap;
  heap.reserve(k + 1);
  std::vector<int> stack;
  stack.push_back(0);
  // Depth-first with explicit stack; each entry carries no bound, so re-check at visit time via the
  // split distance stored alongside.
  std::vector<float> stack_bound;
  stack_bound.push_back(0.f);
  while (!stack.empty()) {
    const int id = stack.back();
    const float bound = stack_bound.back();
    stack.pop_back();
    stack_bound.pop_back();
    if (static_cast<int>(heap.size()) == k && bound >= heap.front().first) continue;
    const Node& n = nodes_[id];
    if (n.dim < 0) {
      for (int i = n.a; i < n.b; ++i) {
        const float d2 = (ordered_[i] - q).squaredNorm();
        if (static_cast<int>(heap.size()) < k) {
          heap.emplace_back(d2, i);
          std::push_heap(heap.begin(), heap.end());
        } else if (d2 < heap.front().first) {
          std::pop_heap(heap.begin(), heap.end());
          heap.back() = {d2, i};
          std::push_heap(heap.begin(), heap.end());
        }
      }
      continue;
    }
    const float diff = q[n.dim] - n.split;
    const int near = diff < 0.f ? id + 1 : n.a;
    const int far = diff < 0.f ? n.a : id + 1;
    // Push far first so near is explored first.
    stack.push_back(far);
    stack_bound.push_back(std::max(bound, diff * diff));
    stack.push_back(near);
    stack_bound.push_back(bound);
  }
  std::sort_heap(heap.begin(), heap.end());
  indices->reserve(heap.size());
  for (const auto& [d2, i] : heap) {
    indices->push_back(order_[i]);
    if (squared_distances) squared_distances->push_back(d2);
  }
}

}  // namespace objscan::recognition
