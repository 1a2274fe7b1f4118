#pragma once
// Axis-aligned bounding box; empty until a point is added.
#include <Eigen/Core>
#include <limits>

namespace objscan::geometry {

struct Aabb3 {
  Eigen::Vector3d min_m = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max_m = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  bool Empty() const { return !(min_m.x() <= max_m.x() && min_m.y() <= max_m.y() && min_m.z() <= max_m.z()); }
  void Extend(const Eigen::Vector3d& p) {
    min_m = min_m.cwiseMin(p);
    max_m = max_m.cwiseMax(p);
  }
  void Extend(const Aabb3& other) {
    if (other.Empty()) return;
    Extend(other.min_m);
    Extend(other.max_m);
  }
  Eigen::Vector3d Center() const { return 0.5 * (min_m + max_m); }
  Eigen::Vector3d Size() const { return Empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(max_m - min_m); }
  double Diagonal() const { return Size().norm(); }
  bool Contains(const Eigen::Vector3d& p, double margin_m = 0.0) const {
    return (p.array() >= min_m.array() - margin_m).all() && (p.array() <= max_m.array() + margin_m).all();
  }
  // Whether the boxes overlap or lie within gap_m of each other along every axis.
  bool Touches(const Aabb3& o, double gap_m) const {
    return (min_m.array() <= o.max_m.array() + gap_m).all() && (o.min_m.array() <= max_m.array() + gap_m).all();
  }
  // Overlap of the XY footprints (strictly positive area), with an optional shrink margin.
  bool FootprintOverlaps(const Aabb3& o, double margin_m = 0.0) const {
    return min_m.x() + margin_m < o.max_m.x() && o.min_m.x() + margin_m < max_m.x() &&
           min_m.y() + margin_m < o.max_m.y() && o.min_m.y() + margin_m < max_m.y();
  }
};

}  // namespace objscan::geometry
