#include "objscan/planning/view_candidates.h"

#include <algorithm>
#include <cmath>

namespace objscan::planning {

CameraFrustum CameraFrustum::FromPinhole(int width_px, int height_px, double fx_px, double fy_px,
                                         double min_range_m, double max_range_m) {
  CameraFrustum f;
  f.tan_half_fov_x = 0.5 * width_px / fx_px;
  f.tan_half_fov_y = 0.5 * height_px / fy_px;
  f.min_range_m = min_range_m;
  f.max_range_m = max_range_m;
  return f;
}

void ViewCandidateOptions::Validate() const {
  config::Require(num_candidates >= 1, "num_candidates", "must be at least 1");
  config::Require(!ring_elevations_deg.empty(), "ring_elevations_deg", "must list at least one elevation");
  for (double e : ring_elevations_deg) config::RequireInRange("ring_elevations_deg", e, -89.0, 89.0);
  config::Require(fov_fill_fraction > 0.0 && fov_fill_fraction <= 1.0, "fov_fill_fraction", "must be in (0, 1]");
  config::RequirePositive("nbv.candidates.max_distance_m", max_distance_m);
  config::RequireNonNegative("range_margin_m", range_margin_m);
  config::RequireNonNegative("min_camera_height_m", min_camera_height_m);
  config::Require(max_camera_height_m >= min_camera_height_m, "max_camera_height_m",
                  "must be >= min_camera_height_m");
  config::RequireInRange("min_pitch_deg", min_pitch_deg, -89.0, 0.0);
  config::RequireInRange("max_pitch_deg", max_pitch_deg, 0.0, 89.0);
}

const char* ToString(ViewValidity validity) {
  switch (validity) {
    case ViewValidity::kValid:
      return "valid";
    case ViewValidity::kOccupied:
      return "occupied";
    case ViewValidity::kUnknown:
      return "unknown";
    case ViewValidity::kUnreachable:
      return "unreachable";
    case ViewValidity::kLineOfSightBlocked:
      return "line_of_sight_blocked";
    case ViewValidity::kRedundant:
      return "redundant";
  }
  return "unknown_validity";
}

std::vector<geometry::Pose3> GenerateViewCandidates(const Eigen::Vector3d& target_world, double radius_m,
                                                    const CameraFrustum& frustum,
                                                    const ViewCandidateOptions& options) {
  const double half_fov = std::atan(std::min(frustum.tan_half_fov_x, frustum.tan_half_fov_y));
  const double fit_m = radius_m / std::sin(options.fov_fill_fraction * half_fov);
  // Closest the object allows: its near side beyond the minimum range; for objects larger than
  // near_radius_cap_m the nearest parts may fall short of it (they are seen from other views).
  const double near_m = frustum.min_range_m + options.range_margin_m + std::min(radius_m, options.near_radius_cap_m);
  const double far_m = frustum.max_range_m - options.range_margin_m - radius_m;   // farthest it allows
  const double distance_m = std::max(near_m, std::min({fit_m, far_m, options.max_distance_m}));

  const double tan_down = std::tan(geometry::DegToRad(-options.min_pitch_deg));
  const double tan_up = std::tan(geometry::DegToRad(options.max_pitch_deg));
  const int rings = static_cast<int>(options.ring_elevations_deg.size());
  std::vector<geometry::Pose3> poses;
  poses.reserve(options.num_candidates);
  for (int k = 0; k < options.num_candidates; ++k) {
    const double azimuth = 2.0 * M_PI * k / options.num_candidates;
    const double elevation = geometry::DegToRad(options.ring_elevations_deg[k % rings]);
    double horizontal_m = distance_m * std::cos(elevation);
    const double z = std::min(options.max_camera_height_m,
                              std::max(options.min_camera_height_m, target_world.z() + distance_m * std::sin(elevation)));
    const double dz = target_world.z() - z;  // > 0: the camera looks up
    // Widen the horizontal distance until the pitch needed to look at the target is within limits.
    if (dz < 0.0 && tan_down > 0.0) horizontal_m = std::max(horizontal_m, -dz / tan_down);
    if (dz > 0.0 && tan_up > 0.0) horizontal_m = std::max(horizontal_m, dz / tan_up);
    horizontal_m = std::max(horizontal_m, 1e-3);
    const Eigen::Vector3d position(target_world.x() + horizontal_m * std::cos(azimuth),
                                   target_world.y() + horizontal_m * std::sin(azimuth), z);
    geometry::Pose3 T_world_camera;
    geometry::CameraPoseLookAt(position, target_world, &T_world_camera);  // never coincident: horizontal > 0
    poses.push_back(T_world_camera);
  }
  return poses;
}

}  // namespace objscan::planning
