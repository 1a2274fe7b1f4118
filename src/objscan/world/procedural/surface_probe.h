#pragma once
// Vertical probing of an object's surface from above: where does a small object placed at (x, y)
// on top of `object` come to rest? Used to put lamps on night stands, monitors on desks...
#include <vector>

#include <Eigen/Core>

#include "objscan/world/scene.h"

namespace objscan::world::procedural {

class SurfaceProbe {
 public:
  explicit SurfaceProbe(const SceneObject& object);
  // Highest point of the object's surface on the vertical line through (x, y) (world frame);
  // returns false when the line misses the object.
  bool TopHeightAt(double x_m, double y_m, double* z_m) const;

 private:
  std::vector<Eigen::Vector3d> vertices_world_;
  std::vector<Eigen::Vector3i> triangles_;
};

}  // namespace objscan::world::procedural
