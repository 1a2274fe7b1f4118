#include "objscan/recognition/objectness.h"

#include <cmath>
#include <limits>

#include "objscan/geometry/aabb.h"

namespace objscan::recognition {

double MeanSquaredNearestDistance(const std::vector<Eigen::Vector3f>& x, const KdTree3& y) {
  if (x.empty()) return 0.0;
  if (y.empty()) return std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (const auto& p : x) {
    float d2 = 0.f;
    y.Nearest(p, &d2);
    sum += d2;
  }
  return sum / static_cast<double>(x.size());
}

double BoundingBoxDiagonal(const std::vector<Eigen::Vector3f>& points) {
  geometry::Aabb3 box;
  for (const auto& p : points) box.Extend(p.cast<double>());
  return box.Diagonal();
}

ObjectnessTerms ComputeObjectness(const std::vector<Eigen::Vector3f>& c_keypoints_in_m,
                                  const KdTree3& c_tree_in_m, const KdTree3& m_tree, double diagonal_c_m) {
  ObjectnessTerms t;
  t.diagonal_m = diagonal_c_m;
  if (c_keypoints_in_m.empty() || m_tree.empty() || !(diagonal_c_m > 0.0)) return t;  // objectness 0
  t.similarity_m2 = MeanSquaredNearestDistance(c_keypoints_in_m, m_tree);
  t.completeness_m2 = MeanSquaredNearestDistance(m_tree.points(), c_tree_in_m);
  t.objectness = std::exp(-std::sqrt(t.similarity_m2 + t.completeness_m2) / diagonal_c_m);
  return t;
}

ObjectnessTerms ComputeObjectness(const std::vector<Eigen::Vector3f>& c_keypoints,
                                  const std::vector<Eigen::Vector3f>& m_keypoints,
                                  const Eigen::Affine3d& T_item_query) {
  const Eigen::Affine3f T = T_item_query.cast<float>();
  std::vector<Eigen::Vector3f> c_in_m(c_keypoints.size());
  for (std::size_t i = 0; i < c_keypoints.size(); ++i) c_in_m[i] = T * c_keypoints[i];
  // A uniform scale in T scales c, hence its diagonal: |det(linear)|^(1/3).
  const double scale = std::cbrt(std::abs(T_item_query.linear().determinant()));
  const KdTree3 c_tree(c_in_m);
  const KdTree3 m_tree(m_keypoints);
  return ComputeObjectness(c_in_m, c_tree, m_tree, scale * BoundingBoxDiagonal(c_keypoints));
}

}  // namespace objscan::recognition
