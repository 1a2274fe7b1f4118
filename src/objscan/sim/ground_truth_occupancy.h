#pragma once
// Occupancy straight from a world::Scene: a cell is occupied when any triangle of a non-floor object
// passes through the band of heights above it (conservative: any overlap of cell and triangle counts).
// When the scene has floor objects, cells with no floor under their centre are unknown (nowhere to
// drive); without floor objects every cell is floor.
#include <vector>

#include "objscan/navigation/occupancy_source.h"
#include "objscan/world/scene.h"

namespace objscan::sim {

class GroundTruthOccupancy : public navigation::OccupancySource {
 public:
  // The grid covers the bounds of the non-floor objects (or of the floor when there are none)
  // plus margin_m on every side.
  explicit GroundTruthOccupancy(const world::Scene& scene, double margin_m = 0.5);

  navigation::OccupancyGrid2D Grid(double min_z_m, double max_z_m, double cell_size_m) const override;

 private:
  std::vector<Eigen::Vector3d> obstacle_triangles_;  // 3 vertices per triangle, world frame
  std::vector<Eigen::Vector3d> floor_triangles_;
  Eigen::Vector2d min_xy_, max_xy_;
};

}  // namespace objscan::sim
