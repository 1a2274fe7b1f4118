#include "objscan/scanning/scene_limits.h"

#include <cmath>
#include <cstdio>

#include "objscan/common/error.h"
#include "objscan/common/limits.h"

namespace objscan::scanning {
namespace {

std::string Metres(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4g", v);
  return buf;
}

}  // namespace

void CheckSceneLimits(const world::Scene& scene, const SystemConfig& config, const std::string& spec) {
  const std::size_t triangles = scene.NumTriangles();
  if (static_cast<std::int64_t>(triangles) > config.scene.max_triangles) {
    throw InputError(spec + ": the scene has " + std::to_string(triangles) + " triangles, more than scene.max_triangles = " +
                     std::to_string(config.scene.max_triangles) + " (raise it with --set scene.max_triangles=N if memory allows)");
  }
  const geometry::Aabb3 bounds = scene.Bounds();
  if (bounds.Empty()) return;
  const Eigen::Vector3d size = bounds.max_m - bounds.min_m;
  const std::string spans = Metres(size.x()) + " x " + Metres(size.y()) + " x " + Metres(size.z()) + " m";
  if (!size.allFinite() || size.maxCoeff() > config.scene.max_extent_m) {
    throw InputError(spec + ": the scene spans " + spans + ", more than scene.max_extent_m = " +
                     Metres(config.scene.max_extent_m) +
                     " m (the map grids grow with it; raise it with --set scene.max_extent_m=M if memory allows)");
  }
  // The dense grids over the scene (the maps cover what the robot saw of it, the evaluation's grid
  // the scene and two voxels around it).
  const double map_margin_m = 0.0;
  auto check = [&](const char* key, double cell_m, int dims, double margin_m, std::size_t max_cells, const char* grid) {
    double cells = 1.0;
    for (int d = 0; d < dims; ++d) cells *= std::max(1.0, std::ceil((size[d] + 2.0 * margin_m) / cell_m));
    if (cells > static_cast<double>(max_cells)) {
      char count[32];
      std::snprintf(count, sizeof(count), "%.3g", cells);
      throw InputError(spec + ": the scene (" + spans + ") needs a " + grid + " of " + count + " cells at " + key +
                       " = " + Metres(cell_m) + " m, more than the " + std::to_string(max_cells) +
                       " objscan builds (a coarser " + key + " or a smaller scene)");
    }
  };
  check("navigation.cell_size_m", config.navigation.cell_size_m, 2, map_margin_m, limits::kMaxGrid2dCells,
        "navigation grid");
  check("frontiers.cell_size_m", config.frontiers.cell_size_m, 2, map_margin_m, limits::kMaxGrid2dCells,
        "frontier grid");
  if (config.recognition.space_weight > 0.0) {  // the only user of the occupancy map's dense snapshot
    check("occupancy.resolution_m", config.occupancy.resolution_m, 3, map_margin_m,
          limits::kMaxOccupancySnapshotCells, "occupancy grid");
  }
  check("eval.coverage_voxel_size_m", config.eval.coverage_voxel_size_m, 3, 2.0 * config.eval.coverage_voxel_size_m,
        limits::kMaxEvaluationGridCells, "evaluation grid");
}

}  // namespace objscan::scanning
