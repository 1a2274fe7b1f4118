#include "objscan/world/procedural/part_builder.h"

#include <cmath>

#include "objscan/common/union_find.h"

namespace objscan::world::procedural {

using Eigen::Vector3d;

void PartBuilder::Box(const Vector3d& min_m, const Vector3d& max_m) {
  Add(geometry::MakeBox(min_m.cwiseMin(max_m), min_m.cwiseMax(max_m)), Eigen::Affine3d::Identity());
}

void PartBuilder::BoxYaw(const Vector3d& center_m, const Vector3d& size_m, double yaw_rad) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.translate(center_m).rotate(Eigen::AngleAxisd(yaw_rad, Vector3d::UnitZ()));
  Add(geometry::MakeBox(size_m), T);
}

void PartBuilder::BoxPitch(const Vector3d& center_m, const Vector3d& size_m, double pitch_rad) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.translate(center_m).rotate(Eigen::AngleAxisd(pitch_rad, Vector3d::UnitY()));
  Add(geometry::MakeBox(size_m), T);
}

void PartBuilder::BoxRoll(const Vector3d& center_m, const Vector3d& size_m, double roll_rad) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.translate(center_m).rotate(Eigen::AngleAxisd(roll_rad, Vector3d::UnitX()));
  Add(geometry::MakeBox(size_m), T);
}

void PartBuilder::CylinderZ(double x_m, double y_m, double z0_m, double z1_m, double radius_m, int segments) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.translate(Vector3d(x_m, y_m, 0.5 * (z0_m + z1_m)));
  Add(geometry::MakeCylinder(radius_m, std::abs(z1_m - z0_m), segments), T);
}

void PartBuilder::FrustumZ(double x_m, double y_m, double z0_m, double z1_m, double r0_m, double r1_m,
                           int segments) {
  geometry::TriangleMesh m;
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * M_PI * i / segments;
    const double c = std::cos(a), s = std::sin(a);
    m.vertices.emplace_back(static_cast<float>(x_m + r0_m * c), static_cast<float>(y_m + r0_m * s),
                            static_cast<float>(z0_m));
    m.vertices.emplace_back(static_cast<float>(x_m + r1_m * c), static_cast<float>(y_m + r1_m * s),
                            static_cast<float>(z1_m));
  }
  const int bottom = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(static_cast<float>(x_m), static_cast<float>(y_m), static_cast<float>(z0_m));
  m.vertices.emplace_back(static_cast<float>(x_m), static_cast<float>(y_m), static_cast<float>(z1_m));
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    const int b0 = 2 * i, t0 = 2 * i + 1, b1 = 2 * j, t1 = 2 * j + 1;
    m.triangles.emplace_back(b0, b1, t1);
    m.triangles.emplace_back(b0, t1, t0);
    if (r0_m > 0.0) m.triangles.emplace_back(bottom, b1, b0);
    if (r1_m > 0.0) m.triangles.emplace_back(bottom + 1, t0, t1);
  }
  geometry::RemoveDegenerateTriangles(&m);
  Add(m, Eigen::Affine3d::Identity());
}

void PartBuilder::Rod(const Vector3d& a_m, const Vector3d& b_m, double radius_m, int segments) {
  const Vector3d d = b_m - a_m;
  const double length = d.norm();
  if (length <= 0.0) return;
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.translate(0.5 * (a_m + b_m)).rotate(Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), d / length));
  Add(geometry::MakeCylinder(radius_m, length, segments), T);
}

void PartBuilder::Sphere(const Vector3d& center_m, double radius_m, int segments) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.translate(center_m);
  Add(geometry::MakeSphere(radius_m, segments), T);
}

void PartBuilder::Ellipsoid(const Vector3d& center_m, const Vector3d& radii_m, int segments) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.translate(center_m).scale(radii_m);
  Add(geometry::MakeSphere(1.0, segments), T);
}

void PartBuilder::EllipticCylinderZ(double x_m, double y_m, double z0_m, double z1_m, double rx_m, double ry_m,
                                    int segments) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.translate(Vector3d(x_m, y_m, 0.5 * (z0_m + z1_m))).scale(Vector3d(rx_m, ry_m, 1.0));
  Add(geometry::MakeCylinder(1.0, std::abs(z1_m - z0_m), segments), T);
}

void PartBuilder::Add(const geometry::TriangleMesh& part, const Eigen::Affine3d& T) {
  const geometry::TriangleMesh placed = geometry::Transformed(part, T);
  part_bounds_.push_back(geometry::Bounds(placed));
  geometry::Append(placed, &mesh_);
}

int PartBuilder::NumConnectedGroups(double tolerance_m) const {
  const int n = static_cast<int>(part_bounds_.size());
  UnionFind parts(n);
  int groups = n;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (!part_bounds_[i].Touches(part_bounds_[j], tolerance_m)) continue;
      if (parts.Find(i) != parts.Find(j)) {
        parts.Union(i, j);
        --groups;
      }
    }
  }
  return groups;
}

geometry::TriangleMesh PartBuilder::Finish() const {
  geometry::TriangleMesh out = mesh_;
  if (out.vertices.empty()) return out;
  Eigen::Vector3f lo = out.vertices.front(), hi = out.vertices.front();
  for (const auto& v : out.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  // Subtracting the float minimum makes the lowest vertex exactly 0.
  const Eigen::Vector3f shift(0.5f * (lo.x() + hi.x()), 0.5f * (lo.y() + hi.y()), lo.z());
  for (auto& v : out.vertices) v -= shift;
  return out;
}

}  // namespace objscan::world::procedural
