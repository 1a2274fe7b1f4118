#pragma once
// Where the navigator's 2-D occupancy comes from: the ground-truth scene (tests, `render`) now, the
// robot's own map later. One call per map update, returning a whole grid (no per-cell virtual calls).
#include "objscan/navigation/occupancy_grid.h"

namespace objscan::navigation {

class OccupancySource {
 public:
  virtual ~OccupancySource() = default;
  // The grid of `cell_size_m` cells over the area the source knows. A cell is occupied when
  // something lies inside the band of heights (min_z_m, max_z_m) above it, unknown when the source
  // cannot tell (unobserved, or no floor to drive on), free otherwise.
  virtual OccupancyGrid2D Grid(double min_z_m, double max_z_m, double cell_size_m) const = 0;
};

}  // namespace objscan::navigation
