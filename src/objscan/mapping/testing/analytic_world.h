#pragma once
// Test fixture (header only, not part of the library): a world of axis-aligned boxes rendered into
// depth frames by exact ray-box intersection, with optional Gaussian depth noise. Gives mapping and
// segmentation tests known answers without the ray-casting simulator.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "objscan/common/rng.h"
#include "objscan/geometry/pose.h"
#include "objscan/platform/depth_frame.h"

namespace objscan::mapping::testing {

struct AnalyticBox {
  Eigen::Vector3d min_m;
  Eigen::Vector3d max_m;
  std::int32_t instance = 1;
};

struct AnalyticWorld {
  std::vector<AnalyticBox> boxes;

  void Add(const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m, std::int32_t instance) {
    boxes.push_back({min_m, max_m, instance});
  }

  // Distance along the unit ray to the first box surface (infinity when none); *instance and
  // *normal of the face hit.
  double Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, std::int32_t* instance,
              Eigen::Vector3d* normal) const {
    double best = std::numeric_limits<double>::infinity();
    for (const AnalyticBox& b : boxes) {
      double t0 = 0.0, t1 = best;
      int axis = -1;
      double sign = 0.0;
      bool hit = true;
      for (int a = 0; a < 3 && hit; ++a) {
        if (std::fabs(dir[a]) < 1e-12) {
          if (origin[a] < b.min_m[a] || origin[a] > b.max_m[a]) hit = false;
          continue;
        }
        double ta = (b.min_m[a] - origin[a]) / dir[a];
        double tb = (b.max_m[a] - origin[a]) / dir[a];
        double s = -1.0;  // entering through the min face
        if (ta > tb) {
          std::swap(ta, tb);
          s = 1.0;
        }
        if (ta > t0) {
          t0 = ta;
          axis = a;
          sign = s;
        }
        if (tb < t1) t1 = tb;
        if (t0 > t1) hit = false;
      }
      if (hit && axis >= 0 && t0 < best) {
        best = t0;
        *instance = b.instance;
        *normal = Eigen::Vector3d::Zero();
        (*normal)[axis] = sign;
      }
    }
    return best;
  }

  // Renders a frame; noise sigma(z) = base + quadratic * z^2 when rng != nullptr.
  platform::DepthFrame Render(const geometry::Pose3& T_world_camera, Rng* rng, double sigma_base_m = 0.001,
                         double sigma_quadratic_per_m = 0.0015,
                         const platform::CameraIntrinsics& intrinsics = platform::CameraIntrinsics()) const {
    platform::DepthFrame frame;
    frame.intrinsics = intrinsics;
    frame.T_world_camera = T_world_camera;
    const std::size_t n = static_cast<std::size_t>(intrinsics.NumPixels());
    frame.depth_m.assign(n, 0.f);
    frame.gt_instance.assign(n, 0);
    frame.gt_normal_world.assign(n, Eigen::Vector3f::Zero());
    const Eigen::Vector3d origin = T_world_camera.translation();
    const Eigen::Matrix3d R = T_world_camera.rotation();
    for (int v = 0; v < intrinsics.height_px; ++v) {
      for (int u = 0; u < intrinsics.width_px; ++u) {
        const Eigen::Vector3d ray_camera = intrinsics.RayCamera(u, v);  // z = 1
        const Eigen::Vector3d dir = (R * ray_camera).normalized();
        std::int32_t instance = 0;
        Eigen::Vector3d normal;
        const double dist = Cast(origin, dir, &instance, &normal);
        if (!std::isfinite(dist)) continue;
        double z = dist / ray_camera.norm();
        if (z < intrinsics.min_range_m || z > intrinsics.max_range_m) continue;
        if (rng) z += rng->Normal(0.0, sigma_base_m + sigma_quadratic_per_m * z * z);
        const std::size_t i = static_cast<std::size_t>(v) * intrinsics.width_px + u;
        frame.depth_m[i] = static_cast<float>(z);
        frame.gt_instance[i] = instance;
        frame.gt_normal_world[i] = normal.cast<float>();
      }
    }
    return frame;
  }
};

// Camera at `position` looking at `target` (asserts they differ).
inline geometry::Pose3 LookAt(const Eigen::Vector3d& position, const Eigen::Vector3d& target) {
  geometry::Pose3 T = geometry::Pose3::Identity();
  geometry::CameraPoseLookAt(position, target, &T);
  return T;
}

}  // namespace objscan::mapping::testing
