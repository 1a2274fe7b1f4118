#pragma once
// Normals of a bare point set (when a query comes without the map's normals): PCA of the k nearest
// neighbours, oriented away from the point set's centroid (outward on objects).
#include <Eigen/Core>
#include <vector>

namespace objscan::recognition {

std::vector<Eigen::Vector3f> EstimateNormals(const std::vector<Eigen::Vector3f>& points, int neighbours = 12);

}  // namespace objscan::recognition
