#include "objscan/navigation/occupancy_grid.h"

#include <algorithm>

#include "objscan/common/error.h"
#include "objscan/common/limits.h"

namespace objscan::navigation {

OccupancyGrid2D OccupancyGrid2D::Covering(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy,
                                          double cell_size_m, CellState state) {
  if (!(cell_size_m > 0.0)) throw InputError("occupancy grid: cell_size_m must be > 0");
  if (!min_xy.allFinite() || !max_xy.allFinite() || !(max_xy.x() >= min_xy.x()) || !(max_xy.y() >= min_xy.y())) {
    throw InputError("occupancy grid: bad extent");
  }
  OccupancyGrid2D grid;
  grid.cell_size_m = cell_size_m;
  grid.origin_m = min_xy;
  grid.width = std::max(1, static_cast<int>(std::ceil((max_xy.x() - min_xy.x()) / cell_size_m)));
  grid.height = std::max(1, static_cast<int>(std::ceil((max_xy.y() - min_xy.y()) / cell_size_m)));
  if (static_cast<double>(grid.width) * grid.height > static_cast<double>(limits::kMaxGrid2dCells)) {
    throw InputError("occupancy grid: extent too large for cell size " + std::to_string(cell_size_m) + " m");
  }
  grid.cells.assign(static_cast<std::size_t>(grid.width) * grid.height, state);
  return grid;
}

std::size_t OccupancyGrid2D::Count(CellState state) const {
  return static_cast<std::size_t>(std::count(cells.begin(), cells.end(), state));
}

}  // namespace objscan::navigation
