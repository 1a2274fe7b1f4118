#include "objscan/world/procedural/surface_probe.h"

#include <cmath>

namespace objscan::world::procedural {

SurfaceProbe::SurfaceProbe(const SceneObject& object) : triangles_(object.mesh.triangles) {
  vertices_world_.reserve(object.mesh.vertices.size());
  for (const auto& v : object.mesh.vertices) vertices_world_.push_back(object.T_world_object * v.cast<double>());
}

bool SurfaceProbe::TopHeightAt(double x_m, double y_m, double* z_m) const {
  bool hit = false;
  double best = 0.0;
  for (const auto& t : triangles_) {
    const Eigen::Vector3d& a = vertices_world_[t[0]];
    const Eigen::Vector3d& b = vertices_world_[t[1]];
    const Eigen::Vector3d& c = vertices_world_[t[2]];
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(det) < 1e-14) continue;  // vertical triangle: seen edge-on from above
    const double u = ((x_m - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y_m - a.y())) / det;
    const double v = ((b.x() - a.x()) * (y_m - a.y()) - (x_m - a.x()) * (b.y() - a.y())) / det;
    if (u < -1e-9 || v < -1e-9 || u + v > 1.0 + 1e-9) continue;
    const double z = a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
    if (!hit || z > best) best = z;
    hit = true;
  }
  if (hit) *z_m = best;
  return hit;
}

}  // namespace objscan::world::procedural
