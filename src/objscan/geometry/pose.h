#pragma once
// Rigid transforms. T_a_b maps points from frame b into frame a: p_a = T_a_b * p_b.
// World frame: metres, Z up. Camera (optical) frame: X right, Y down, Z forward.
#include <Eigen/Geometry>

namespace objscan::geometry {

using Pose3 = Eigen::Isometry3d;

// SDF/URDF convention: R = Rz(yaw) * Ry(pitch) * Rx(roll) (fixed axes X, then Y, then Z).
Pose3 PoseFromXyzRpy(double x, double y, double z, double roll_rad, double pitch_rad, double yaw_rad);

// Camera pose from a position and a viewing direction given as yaw (about world Z, 0 = +X) and pitch
// (positive looks up). The camera's image X axis stays horizontal (no roll).
Pose3 CameraPoseFromYawPitch(const Eigen::Vector3d& position_world, double yaw_rad, double pitch_rad);

// Camera pose at `position_world` looking at `target_world`, image X horizontal.
// Returns false (and leaves *T_world_camera untouched) when the two points coincide.
bool CameraPoseLookAt(const Eigen::Vector3d& position_world, const Eigen::Vector3d& target_world,
                      Pose3* T_world_camera);

// Yaw (about Z) and pitch of the optical axis of a camera pose.
void YawPitchOfCamera(const Pose3& T_world_camera, double* yaw_rad, double* pitch_rad);

inline double DegToRad(double deg) { return deg * M_PI / 180.0; }
inline double RadToDeg(double rad) { return rad * 180.0 / M_PI; }
// Wraps an angle to (-pi, pi].
double WrapAngle(double angle_rad);

}  // namespace objscan::geometry
