#pragma once
// A static 3-D kd-tree over float points (flat arrays, no allocation per query): nearest neighbour
// and k nearest neighbours. Used by Lloyd relaxation, alignment (ICP) and objectness, where a query
// touches a few hundred to a few thousand points many times.
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <vector>

namespace objscan::recognition {

class KdTree3 {
 public:
  KdTree3() = default;
  explicit KdTree3(const std::vector<Eigen::Vector3f>& points) { Build(points); }

  // Copies the points; indices returned by queries refer to this vector.
  void Build(const std::vector<Eigen::Vector3f>& points);

  bool empty() const { return points_.empty(); }
  std::size_t size() const { return points_.size(); }
  const std::vector<Eigen::Vector3f>& points() const { return points_; }

  // Index of the point nearest to q and its squared distance; -1 when the tree is empty.
  int Nearest(const Eigen::Vector3f& q, float* squared_distance) const;
  // How NearestBounded walks the tree (the same answer either way, but for the choice among points
  // at exactly the same distance): kSplitPlanes prunes by the distance to each split plane (cheap per
  // node, and enough when the bound is small); kBoxes by the distance to each node's bounds (which
  // a query far from the points needs: every split plane lies within a large bound); kAuto chooses
  // by the bound.
  enum class Walk { kAuto, kSplitPlanes, kBoxes };
  // Nearest point strictly closer than sqrt(bound_d2), or `hint` (with its distance) when none is:
  // pass a good guess (e.g. last ICP round's correspondence) as hint with bound_d2 = its squared
  // distance and the search prunes almost everything. Returns -1 when nothing is within the bound
  // and no hint is given.
  int NearestBounded(const Eigen::Vector3f& q, float bound_d2, int hint, float* squared_distance,
                     Walk walk = Walk::kAuto) const;
  // Up to k nearest points, closest first (indices and squared distances).
  void KNearest(const Eigen::Vector3f& q, int k, std::vector<int>* indices,
                std::vector<float>* squared_distances) const;

 private:
  // Nodes in preorder: an inner node's left child is the next node.
  struct Node {
    std::int32_t dim = -1;  // leaf when < 0
    float split = 0.f;
    std::int32_t a = 0;     // inner: right child; leaf: first point (in ordered_)
    std::int32_t b = 0;     // leaf: one past the last point
    // Tight bounds of the node's points: a query far outside the set prunes by them, where the
    // split planes alone leave the outer cells unbounded.
    float lo[3] = {0.f, 0.f, 0.f};
    float hi[3] = {0.f, 0.f, 0.f};
  };
  // Squared distance from q to the node's bounds.
  static float BoxDistance2(const Node& n, float qx, float qy, float qz) {
    const float dx = std::max(0.f, std::max(n.lo[0] - qx, qx - n.hi[0]));
    const float dy = std::max(0.f, std::max(n.lo[1] - qy, qy - n.hi[1]));
    const float dz = std::max(0.f, std::max(n.lo[2] - qz, qz - n.hi[2]));
    return dx * dx + dy * dy + dz * dz;
  }
  int BuildNode(int begin, int end);
  // Returns the ordered_ index of the nearest point closer than *best_d2 (or *best unchanged).
  // Search prunes by the nodes' bounds (for unbounded queries, also far from the points);
  // SearchNear by the split planes only, cheaper per node when *best_d2 is already small.
  void Search(const Eigen::Vector3f& q, int* best, float* best_d2) const;
  void SearchNear(const Eigen::Vector3f& q, int* best, float* best_d2) const;

  std::vector<Eigen::Vector3f> points_;
  std::vector<Eigen::Vector3f> ordered_;  // points_ in leaf order: leaves scan contiguous memory
  std::vector<std::int32_t> order_;       // ordered_[i] == points_[order_[i]]
  std::vector<Node> nodes_;
  float split_planes_max_d2_ = 0.f;  // NearestBounded's kAuto walks by boxes beyond this bound
};

}  // namespace objscan::recognition
