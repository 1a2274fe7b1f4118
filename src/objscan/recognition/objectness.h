#pragma once
// Model-driven objectness, exactly the paper's eq. (1):
//   O(c, m) = exp(-(d(c, m) + d(m, c))^(1/2) / Diag(c)),
//   d(X, Y) = mean over X's keypoints of the squared distance to the nearest keypoint of Y,
// measured after c has been aligned to m. d(c, m) is the similarity of c to m, d(m, c) the
// completeness of c with respect to m; Diag(c) is the diagonal of c's bounding box.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "objscan/recognition/kd_tree.h"

namespace objscan::recognition {

// d(X, Y) with Y given by a kd-tree over its keypoints; 0 for an empty X, +inf for an empty Y.
double MeanSquaredNearestDistance(const std::vector<Eigen::Vector3f>& x, const KdTree3& y);

struct ObjectnessTerms {
  double similarity_m2 = 0.0;    // d(c, m)
  double completeness_m2 = 0.0;  // d(m, c)
  double diagonal_m = 0.0;       // Diag(c)
  double objectness = 0.0;       // O(c, m)
};

// c's keypoints already expressed in m's frame; `diagonal_c_m` is Diag(c) in that frame.
ObjectnessTerms ComputeObjectness(const std::vector<Eigen::Vector3f>& c_keypoints_in_m,
                                  const KdTree3& c_tree_in_m, const KdTree3& m_tree, double diagonal_c_m);

// Convenience: transforms c's keypoints by T_item_query (rigid, or with uniform scale) into m's frame
// and uses the diagonal of c's own axis-aligned bounding box (scaled like c) as Diag(c).
ObjectnessTerms ComputeObjectness(const std::vector<Eigen::Vector3f>& c_keypoints,
                                  const std::vector<Eigen::Vector3f>& m_keypoints,
                                  const Eigen::Affine3d& T_item_query);

// Diagonal of the axis-aligned bounding box of a point set (0 when empty).
double BoundingBoxDiagonal(const std::vector<Eigen::Vector3f>& points);

}  // namespace objscan::recognition
