#include "objscan/scanning/report/completion_check.h"

#include "objscan/geometry/point_cloud.h"

namespace objscan::scanning {

double ShareOutsideModelBox(const std::vector<Eigen::Vector3f>& points_world,
                            const std::vector<Eigen::Vector3f>& model_points, const geometry::Pose3& T_world_model,
                            double margin_m) {
  if (points_world.empty()) return 0.0;
  if (model_points.empty()) return 1.0;
  const geometry::Aabb3 box = geometry::Bounds(model_points);
  const Eigen::Isometry3d T_model_world = T_world_model.inverse();
  std::size_t outside = 0;
  for (const Eigen::Vector3f& p : points_world) {
    if (!box.Contains(T_model_world * p.cast<double>(), margin_m)) ++outside;
  }
  return static_cast<double>(outside) / static_cast<double>(points_world.size());
}

}  // namespace objscan::scanning
