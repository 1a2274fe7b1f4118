#pragma once
// A static 3-D kd-tree over float points (flat arrays, no allocation per query): nearest neighbour
// and k nearest neighbours. Used by Lloyd relaxation, alignment (ICP) and objectness, where a query
// touches a few hundred to a few thousand points many times.
#include <Eigen/Core>
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
  // Up to k nearest points, closest first (indices and squared distances).
  void KNearest(const Eigen::Vector3f& q, int k, std::vector<int>* indices,
                std::vector<float>* squared_distances) const;

 private:
  struct Node {
    // Leaf when dim < 0: points order_[begin, end). Otherwise children at left/right.
    std::int32_t dim = -1;
    float split = 0.f;
    std::int32_t left = -1, right = -1;
    std::int32_t begin = 0, end = 0;
  };
  int BuildNode(int begin, int end);
  void NearestRec(int node, const Eigen::Vector3f& q, int* best, float* best_d2) const;

  std::vector<Eigen::Vector3f> points_;
  std::vector<Eigen::Vector3f> ordered_;  // points_ in leaf order: leaves scan contiguous memory
  std::vector<std::int32_t> order_;       // ordered_[i] == points_[order_[i]]
  std::vector<Node> nodes_;
};

}  // namespace objscan::recognition
