#include "objscan/scanning/completion_check.h"

namespace objscan::scanning {

double ShareOutsideModelBox(const std::vector<Eigen::Vector3f>& points_world,
                            const std::vector<Eigen::Vector3f>& model_points, const geometry::Pose3& T_world_model,
                            double margin_m) {
  if (points_world.empty()) return 0.0;
  if (model_points.empty()) return 1.0;
  Eigen::Vector3f lo = model_points.front(), hi = model_points.front();
  for (const Eigen::Vector3f& p : model_points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3f margin = Eigen::Vector3f::Constant(static_cast<float>(margin_m));
  lo -= margin;
  hi += margin;
  const Eigen::Isometry3f T_model_world = T_world_model.inverse().cast<float>();
  std::size_t outside = 0;
  for (const Eigen::Vector3f& p : points_world) {
    const Eigen::Vector3f q = T_model_world * p;
    if ((q.array() < lo.array()).any() || (q.array() > hi.array()).any()) ++outside;
  }
  return static_cast<double>(outside) / static_cast<double>(points_world.size());
}

}  // namespace objscan::scanning
