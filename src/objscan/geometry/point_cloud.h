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

inline Aabb3 Bounds(const std::vector<Eigen::Vector3f>& points) {
  Aabb3 box;
  for (const auto& p : points) box.Extend(p.cast<double>());
  return box;
}

inline Aabb3 Bounds(const PointCloud& cloud) { return Bounds(cloud.points); }

}  // namespace objscan::geometry
