#include "objscan/geometry/pose.h"

#include <cmath>

namespace objscan::geometry {

Pose3 PoseFromXyzRpy(double x, double y, double z, double roll_rad, double pitch_rad, double yaw_rad) {
  Pose3 T = Pose3::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

Pose3 CameraPoseFromYawPitch(const Eigen::Vector3d& position_world, double yaw_rad, double pitch_rad) {
  const Eigen::Vector3d forward(std::cos(pitch_rad) * std::cos(yaw_rad), std::cos(pitch_rad) * std::sin(yaw_rad),
                                std::sin(pitch_rad));
  // Image X (right) is horizontal: forward x up, normalised; for yaw it is (sin yaw, -cos yaw, 0).
  const Eigen::Vector3d right(std::sin(yaw_rad), -std::cos(yaw_rad), 0.0);
  const Eigen::Vector3d down = forward.cross(right);
  Pose3 T = Pose3::Identity();
  T.linear().col(0) = right;
  T.linear().col(1) = down;
  T.linear().col(2) = forward;
  T.translation() = position_world;
  return T;
}

bool CameraPoseLookAt(const Eigen::Vector3d& position_world, const Eigen::Vector3d& target_world,
                      Pose3* T_world_camera) {
  const Eigen::Vector3d d = target_world - position_world;
  const double horizontal = std::hypot(d.x(), d.y());
  if (d.norm() < 1e-12) return false;
  const double yaw = horizontal > 1e-12 ? std::atan2(d.y(), d.x()) : 0.0;
  const double pitch = std::atan2(d.z(), horizontal);
  *T_world_camera = CameraPoseFromYawPitch(position_world, yaw, pitch);
  return true;
}

void YawPitchOfCamera(const Pose3& T_world_camera, double* yaw_rad, double* pitch_rad) {
  const Eigen::Vector3d forward = T_world_camera.linear().col(2);
  *yaw_rad = std::atan2(forward.y(), forward.x());
  *pitch_rad = std::atan2(forward.z(), std::hypot(forward.x(), forward.y()));
}

double WrapAngle(double angle_rad) {
  double a = std::fmod(angle_rad + M_PI, 2.0 * M_PI);
  if (a <= 0.0) a += 2.0 * M_PI;
  return a - M_PI;
}

}  // namespace objscan::geometry
