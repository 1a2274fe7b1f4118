#pragma once
// objscan's poses as robot middleware carries them (geometry_msgs/Transform and Pose: a translation
// and a unit quaternion x, y, z, w). objscan's camera frame is the optical frame of REP 103 (z
// forward, x right, y down), so T_world_camera is world -> <camera>_optical_frame as it is.
#include <array>

#include "objscan/geometry/pose.h"
#include "objscan/platform/platform.h"

namespace objscan::ros_bridge {

struct TransformBuffer {
  std::array<double, 3> translation_m{};
  std::array<double, 4> rotation_xyzw{0.0, 0.0, 0.0, 1.0};
};

TransformBuffer TransformFromPose(const geometry::Pose3& pose);
// The quaternion is normalised (messages round it); throws InputError naming `what` when it is not
// finite or of zero length.
geometry::Pose3 PoseFromTransform(const TransformBuffer& transform, const std::string& what);

// The base on the floor as world -> base_link (z = 0, turned about z by theta).
TransformBuffer TransformFromBase(const platform::BasePose& base);
// The heading and floor position of a base_link transform (its tilt, if any, is dropped).
platform::BasePose BaseFromTransform(const TransformBuffer& transform, const std::string& what);

}  // namespace objscan::ros_bridge
