#pragma once
// Floor frontiers: observed floor cells next to unexplored cells, clustered into navigation goals.
// The paper sends the robot to them when no object is in view and stops when none are left.
#include <Eigen/Core>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/mapping/occupancy_map.h"
#include "objscan/mapping/planes.h"
#include "objscan/mapping/surface_map.h"

namespace objscan::mapping {

struct FrontierOptions {
  double cell_size_m = 0.05;
  int min_floor_elements_per_cell = 3;  // floor-tagged surface elements that make a cell observed
  int min_cluster_cells = 4;            // smaller clusters are noise, not goals
  // Cells behind a detected wall (by more than this) are outside the room and never frontiers.
  double wall_margin_m = 0.1;
  // An unknown cell within this many cells of an obstacle (an occupied voxel between the probe
  // height just above the floor and obstacle_probe_height_m above it, about the robot's height)
  // is the hidden underside or back of that obstacle (a wardrobe, the knee space of a desk, a gap
  // between a bed and a night stand), not open floor the robot could drive to.
  int obstacle_clearance_cells = 1;
  double obstacle_probe_height_m = 1.5;

  template <class V>
  void Visit(V& v) {
    v("cell_size_m", cell_size_m);
    v("min_floor_elements_per_cell", min_floor_elements_per_cell);
    v("min_cluster_cells", min_cluster_cells);
    v("wall_margin_m", wall_margin_m);
    v("obstacle_clearance_cells", obstacle_clearance_cells);
    v("obstacle_probe_height_m", obstacle_probe_height_m);
  }
  void Validate() const;
};

struct FrontierGoal {
  Eigen::Vector2d centroid_m = Eigen::Vector2d::Zero();  // world XY
  int size_cells = 0;
  std::vector<Eigen::Vector2d> cells_m;  // centres of its cells
};

// A floor cell is observed when it holds enough floor-tagged elements; a neighbour (4-connected) is
// unexplored when it is not observed floor, its centre is not beyond a detected wall, the
// occupancy just above the floor there is unknown (occupied means an obstacle such as a wall or
// furniture; free means rays passed over it) and no obstacle stands within
// obstacle_clearance_cells of it.
// Frontier cells are clustered 8-connected; goals are sorted by size, largest first.
std::vector<FrontierGoal> FindFloorFrontiers(const SurfaceMap& surface, const OccupancyMap& occupancy,
                                             const StructureResult& structure, const FrontierOptions& options);

}  // namespace objscan::mapping
