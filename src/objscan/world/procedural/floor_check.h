#pragma once
// Free-floor check of a scene on a 2-D grid: is the floor space a robot of a given width can use
// one connected region, and can the robot get close to every object?
//
// Grid: cells of `cell_m` over the floor's XY bounds. A cell is free when its centre lies on a floor
// triangle (Category::kFloor) and outside every obstacle footprint. An obstacle footprint is the XY
// bounding box of any non-floor object whose height range meets [kObstacleMinZ, kObstacleMaxZ]
// (conservative for L-shaped or rotated objects). The free space is eroded by passage_m / 2 (a cell
// stays free when no blocked cell centre is closer than passage_m / 2), so a passage narrower than
// passage_m disconnects. The eroded free space must be one 4-connected component, and every
// furniture object must have an eroded-free cell within max_reach_m of its footprint.
#include <cstdint>
#include <vector>

#include "objscan/world/scene.h"

namespace objscan::world::procedural {

constexpr double kObstacleMinZ = 0.02;
constexpr double kObstacleMaxZ = 1.9;

struct FloorConnectivityReport {
  bool ok = false;  // connected (exactly one component) and every furniture object reachable
  int num_components = 0;        // 4-connected components of the eroded free space
  std::size_t floor_cells = 0;   // cells on the floor
  std::size_t free_cells = 0;    // floor cells outside obstacles
  std::size_t eroded_free_cells = 0;
  std::vector<std::int32_t> unreachable_instances;  // furniture without an eroded-free cell in reach

  // The grid (row-major, y rows): 0 = off floor, 1 = obstacle, 2 = free, 3 = eroded free.
  double cell_m = 0.0;
  double origin_x_m = 0.0, origin_y_m = 0.0;  // min corner of cell (0, 0)
  int width = 0, height = 0;
  std::vector<std::uint8_t> cells;
};

// Throws InputError when the scene has no floor or cell_m <= 0.
FloorConnectivityReport CheckFreeFloor(const Scene& scene, double cell_m = 0.05, double passage_m = 0.8,
                                       double max_reach_m = 1.5);

}  // namespace objscan::world::procedural
