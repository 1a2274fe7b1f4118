#pragma once
// Points with optional normals and per-point integer labels (plain data).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "objscan/geometry/aabb.h"

namespace objscan::geometry {

struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;  // empty or one per point
  std::vector<std::int32_t> labels;      // empty or one per point

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool HasNormals() const { return !points.empty() && normals.size() == points.size(); }
};

inline Aabb3 Bounds(const PointCloud& cloud) {
  Aabb3 box;
  for (const auto& p : cloud.points) box.Extend(p.cast<double>());
  return box;
}

}  // namespace objscan::geometry
