#pragma once
// Builds a furniture mesh from parametric parts (boxes, cylinders, frusta, spheres, rods) given in
// the model frame (metres, Z up, front facing +X), then normalises it: centred in XY, min z = 0.
#include <Eigen/Core>
#include <vector>

#include "objscan/geometry/mesh.h"

namespace objscan::world::procedural {

class PartBuilder {
 public:
  // Axis-aligned box spanning [min, max].
  void Box(const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m);
  void Box(double x0, double y0, double z0, double x1, double y1, double z1) {
    Box(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
  }
  // Box of `size_m` centred at `center_m`, rotated by `yaw_rad` about Z.
  void BoxYaw(const Eigen::Vector3d& center_m, const Eigen::Vector3d& size_m, double yaw_rad);
  // Box of `size_m` centred at `center_m`, rotated by `pitch_rad` about Y (e.g. a reclined back).
  void BoxPitch(const Eigen::Vector3d& center_m, const Eigen::Vector3d& size_m, double pitch_rad);
  // Box of `size_m` centred at `center_m`, rotated by `roll_rad` about X.
  void BoxRoll(const Eigen::Vector3d& center_m, const Eigen::Vector3d& size_m, double roll_rad);
  // Vertical cylinder of radius `radius_m` at (x, y) from z0 to z1.
  void CylinderZ(double x_m, double y_m, double z0_m, double z1_m, double radius_m, int segments = 20);
  // Vertical truncated cone: radius r0 at z0, r1 at z1 (either may be 0 for a cone).
  void FrustumZ(double x_m, double y_m, double z0_m, double z1_m, double r0_m, double r1_m,
                int segments = 20);
  // Cylinder (rod) between two points.
  void Rod(const Eigen::Vector3d& a_m, const Eigen::Vector3d& b_m, double radius_m, int segments = 10);
  void Sphere(const Eigen::Vector3d& center_m, double radius_m, int segments = 16);
  // Ellipsoid with semi-axes `radii_m` (a scaled sphere).
  void Ellipsoid(const Eigen::Vector3d& center_m, const Eigen::Vector3d& radii_m, int segments = 16);
  // Elliptic vertical cylinder (semi-axes rx, ry) from z0 to z1.
  void EllipticCylinderZ(double x_m, double y_m, double z0_m, double z1_m, double rx_m, double ry_m,
                         int segments = 24);
  // Any mesh, transformed.
  void Add(const geometry::TriangleMesh& part, const Eigen::Affine3d& T);

  const geometry::TriangleMesh& mesh() const { return mesh_; }
  // Number of groups of parts that touch (bounding boxes within `tolerance_m`); 1 for a connected model.
  int NumConnectedGroups(double tolerance_m = 1e-3) const;
  std::size_t NumParts() const { return part_bounds_.size(); }
  // The finished mesh: translated so that its XY bounding box is centred on the origin and its
  // lowest vertex lies exactly at z = 0.
  geometry::TriangleMesh Finish() const;

 private:
  geometry::TriangleMesh mesh_;
  std::vector<geometry::Aabb3> part_bounds_;
};

}  // namespace objscan::world::procedural
