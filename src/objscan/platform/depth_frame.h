#pragma once
// A posed depth image: what the sensor gives the method. The ground-truth channels are for
// evaluation only; the method never reads them.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "objscan/geometry/pose.h"

namespace objscan::platform {

struct CameraIntrinsics {
  int width_px = 640;
  int height_px = 480;
  double fx_px = 525.0;
  double fy_px = 525.0;
  double cx_px = 319.5;
  double cy_px = 239.5;
  double min_range_m = 0.5;  // depth (z) below this is invalid
  double max_range_m = 4.0;  // depth (z) beyond this is invalid

  int NumPixels() const { return width_px * height_px; }
  // Unit-z ray direction (z = 1) of pixel centre (u, v) in the camera frame.
  Eigen::Vector3d RayCamera(double u, double v) const {
    return Eigen::Vector3d((u - cx_px) / fx_px, (v - cy_px) / fy_px, 1.0);
  }
  // Projects a camera-frame point; false when behind the camera.
  bool Project(const Eigen::Vector3d& p_camera, double* u, double* v) const {
    if (p_camera.z() <= 0.0) return false;
    *u = fx_px * p_camera.x() / p_camera.z() + cx_px;
    *v = fy_px * p_camera.y() / p_camera.z() + cy_px;
    return true;
  }
};

struct DepthFrame {
  CameraIntrinsics intrinsics;
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();
  std::vector<float> depth_m;                   // row-major, z in metres, 0 = invalid
  std::vector<std::int32_t> gt_instance;        // evaluation only: instance id per pixel, 0 = none
  std::vector<Eigen::Vector3f> gt_normal_world; // evaluation only: true surface normal per pixel

  int width() const { return intrinsics.width_px; }
  int height() const { return intrinsics.height_px; }
  float Depth(int u, int v) const { return depth_m[static_cast<std::size_t>(v) * intrinsics.width_px + u]; }
  // Camera-frame point of a valid pixel.
  Eigen::Vector3d PointCamera(int u, int v) const {
    return intrinsics.RayCamera(u, v) * static_cast<double>(Depth(u, v));
  }
  Eigen::Vector3d PointWorld(int u, int v) const { return T_world_camera * PointCamera(u, v); }
  std::size_t NumValid() const {
    std::size_t n = 0;
    for (float d : depth_m) n += d > 0.f ? 1 : 0;
    return n;
  }
};

}  // namespace objscan::platform
