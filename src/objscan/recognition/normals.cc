#include "objscan/recognition/normals.h"

#include <Eigen/Eigenvalues>

#include "objscan/recognition/kd_tree.h"

namespace objscan::recognition {

std::vector<Eigen::Vector3f> EstimateNormals(const std::vector<Eigen::Vector3f>& points, int neighbours) {
  std::vector<Eigen::Vector3f> normals(points.size(), Eigen::Vector3f::UnitZ());
  if (points.size() < 3) return normals;
  const KdTree3 tree(points);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p.cast<double>();
  centroid /= static_cast<double>(points.size());
  std::vector<int> idx;
  for (std::size_t i = 0; i < points.size(); ++i) {
    tree.KNearest(points[i], neighbours, &idx, nullptr);
    if (idx.size() < 3) continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int j : idx) mean += points[j].cast<double>();
    mean /= static_cast<double>(idx.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (int j : idx) {
      const Eigen::Vector3d d = points[j].cast<double>() - mean;
      cov += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
    Eigen::Vector3d n = solver.eigenvectors().col(0);  // smallest eigenvalue
    if (n.dot(points[i].cast<double>() - centroid) < 0.0) n = -n;
    normals[i] = n.normalized().cast<float>();
  }
  return normals;
}

}  // namespace objscan::recognition
