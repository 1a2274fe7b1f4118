#include "objscan/scanning/coverage_views.h"

#include <cmath>
#include <string>
#include <unordered_set>

#include "objscan/geometry/voxel_key.h"

namespace objscan::scanning {

void CoverageViewOptions::Validate() const {
  config::Require(max_views_per_object >= 0, "scanner.coverage_views.max_views_per_object", "must be >= 0");
  config::Require(min_unseen_voxels >= 1, "scanner.coverage_views.min_unseen_voxels", "must be >= 1");
  config::RequireInRange("scanner.coverage_views.min_objectness", min_objectness, 0.0, 1.0);
  config::RequireNonNegative("scanner.coverage_views.floor_clearance_m", floor_clearance_m);
  config::Require(num_candidates >= 1 && num_candidates <= 256, "scanner.coverage_views.num_candidates",
                  "must be in [1, 256] (got " + std::to_string(num_candidates) + ")");
  config::Require(!ring_elevations_deg.empty(), "scanner.coverage_views.ring_elevations_deg", "must not be empty");
  for (double e : ring_elevations_deg) {
    config::RequireInRange("scanner.coverage_views.ring_elevations_deg", e, -89.0, 89.0);
  }
}

std::vector<Eigen::Vector3f> ModelSurfaceAboveFloor(const std::vector<Eigen::Vector3f>& model_points_world,
                                                    bool has_floor, double floor_height_m, double clearance_m) {
  const double min_z = (has_floor ? floor_height_m : 0.0) + clearance_m;
  std::vector<Eigen::Vector3f> out;
  out.reserve(model_points_world.size());
  for (const Eigen::Vector3f& p : model_points_world) {
    if (p.z() >= min_z) out.push_back(p);
  }
  return out;
}

std::vector<Eigen::Vector3f> UnseenModelPoints(const std::vector<Eigen::Vector3f>& model_points_world,
                                               const std::vector<Eigen::Vector3f>& seen_points_world,
                                               double seen_radius_m) {
  if (!(seen_radius_m > 0.0)) return model_points_world;
  const float inv = static_cast<float>(1.0 / seen_radius_m);
  std::unordered_set<geometry::VoxelKey, geometry::VoxelKeyHash> seen;
  seen.reserve(seen_points_world.size());
  for (const Eigen::Vector3f& p : seen_points_world) seen.insert(geometry::KeyOf(p, inv));
  std::vector<Eigen::Vector3f> out;
  for (const Eigen::Vector3f& p : model_points_world) {
    const geometry::VoxelKey k = geometry::KeyOf(p, inv);
    bool near = false;
    for (int dx = -1; dx <= 1 && !near; ++dx) {
      for (int dy = -1; dy <= 1 && !near; ++dy) {
        for (int dz = -1; dz <= 1 && !near; ++dz) near = seen.count({k.x + dx, k.y + dy, k.z + dz}) > 0;
      }
    }
    if (!near) out.push_back(p);
  }
  return out;
}

}  // namespace objscan::scanning
