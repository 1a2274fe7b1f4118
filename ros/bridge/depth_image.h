#pragma once
// Depth images as robot middleware carries them (ROS 1 and ROS 2 sensor_msgs/Image, CameraInfo) and
// objscan's neutral sensor types (platform::DepthFrame, CameraIntrinsics), converted both ways. Plain
// C++: the ROS glue copies these fields into and out of its messages.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "objscan/platform/depth_frame.h"

namespace objscan::ros_bridge {

// sensor_msgs/Image's fields.
struct ImageBuffer {
  int width = 0;
  int height = 0;
  std::string encoding;      // "32FC1" (metres), "16UC1" (millimetres), "32SC1" (instance ids)
  bool is_bigendian = false;
  std::uint32_t step_bytes = 0;  // bytes per row (rows may be padded)
  std::vector<std::uint8_t> data;
};

// 32FC1 in metres; objscan's invalid depth (0) becomes NaN (REP 118: no return).
ImageBuffer DepthImageFromMetres(const std::vector<float>& depth_m, int width, int height);
// Depth in metres, row-major, 0 = invalid, from a 32FC1 (metres; NaN, infinities and values <= 0
// invalid) or 16UC1 (millimetres; 0 invalid) image, either byte order, rows padded or not. Throws
// InputError naming `what` (the topic) on another encoding or a buffer too small for its size.
std::vector<float> DepthMetresFromImage(const ImageBuffer& image, const std::string& what);

// Ground-truth instance ids per pixel (evaluation only): 32SC1.
ImageBuffer InstanceImage(const std::vector<std::int32_t>& instance, int width, int height);
std::vector<std::int32_t> InstancesFromImage(const ImageBuffer& image, const std::string& what);

// sensor_msgs/CameraInfo's fields objscan reads and writes (plumb_bob, no distortion).
struct CameraInfoBuffer {
  int width = 0;
  int height = 0;
  std::array<double, 9> K{};   // row-major 3x3
  std::array<double, 12> P{};  // row-major 3x4
  std::array<double, 9> R{};   // rectification: identity
};
CameraInfoBuffer CameraInfoFromIntrinsics(const platform::CameraIntrinsics& intrinsics);
// The intrinsics of a camera info; the depth range is not part of a camera info and comes from the
// caller (the node's sensor options). Throws InputError naming `what` on a zero size or focal length.
platform::CameraIntrinsics IntrinsicsFromCameraInfo(const CameraInfoBuffer& info, double min_range_m,
                                                    double max_range_m, const std::string& what);

}  // namespace objscan::ros_bridge
