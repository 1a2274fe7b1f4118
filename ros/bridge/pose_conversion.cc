#include "pose_conversion.h"

#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "objscan/common/error.h"

namespace objscan::ros_bridge {

TransformBuffer TransformFromPose(const geometry::Pose3& pose) {
  TransformBuffer t;
  const Eigen::Vector3d p = pose.translation();
  t.translation_m = {p.x(), p.y(), p.z()};
  const Eigen::Quaterniond q(pose.linear());
  t.rotation_xyzw = {q.x(), q.y(), q.z(), q.w()};
  return t;
}

geometry::Pose3 PoseFromTransform(const TransformBuffer& transform, const std::string& what) {
  const Eigen::Vector3d p(transform.translation_m[0], transform.translation_m[1], transform.translation_m[2]);
  Eigen::Quaterniond q(transform.rotation_xyzw[3], transform.rotation_xyzw[0], transform.rotation_xyzw[1],
                       transform.rotation_xyzw[2]);
  if (!p.allFinite() || !q.coeffs().allFinite() || q.norm() < 1e-9) {
    throw InputError(what + ": transform is not finite or its rotation is not a quaternion");
  }
  q.normalize();
  geometry::Pose3 pose = geometry::Pose3::Identity();
  pose.linear() = q.toRotationMatrix();
  pose.translation() = p;
  return pose;
}

TransformBuffer TransformFromBase(const platform::BasePose& base) {
  TransformBuffer t;
  t.translation_m = {base.xy_m.x(), base.xy_m.y(), 0.0};
  t.rotation_xyzw = {0.0, 0.0, std::sin(0.5 * base.theta_rad), std::cos(0.5 * base.theta_rad)};
  return t;
}

platform::BasePose BaseFromTransform(const TransformBuffer& transform, const std::string& what) {
  const geometry::Pose3 pose = PoseFromTransform(transform, what);
  const Eigen::Vector3d x_axis = pose.linear().col(0);
  platform::BasePose base;
  base.xy_m = pose.translation().head<2>();
  base.theta_rad = std::atan2(x_axis.y(), x_axis.x());
  return base;
}

}  // namespace objscan::ros_bridge
