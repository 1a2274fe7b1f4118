#pragma once
// A 2-D grid over the floor (world XY) saying, per cell, whether the band of heights the robot
// occupies is free, occupied or unknown there. Plain data; row-major, index = iy * width + ix.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

namespace objscan::navigation {

enum class CellState : std::uint8_t { kFree = 0, kOccupied = 1, kUnknown = 2 };

struct OccupancyGrid2D {
  double cell_size_m = 0.05;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // world XY of the outer corner of cell (0, 0)
  int width = 0;                                       // cells along X
  int height = 0;                                      // cells along Y
  std::vector<CellState> cells;

  // A grid of `state` covering [min_xy, max_xy] (at least one cell).
  static OccupancyGrid2D Covering(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, double cell_size_m,
                                  CellState state);

  std::size_t NumCells() const { return cells.size(); }
  bool Contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
  std::size_t Index(int ix, int iy) const { return static_cast<std::size_t>(iy) * width + ix; }
  // Outside the grid everything is unknown.
  CellState At(int ix, int iy) const { return Contains(ix, iy) ? cells[Index(ix, iy)] : CellState::kUnknown; }
  Eigen::Vector2i CellOf(const Eigen::Vector2d& xy) const {
    return Eigen::Vector2i(static_cast<int>(std::floor((xy.x() - origin_m.x()) / cell_size_m)),
                           static_cast<int>(std::floor((xy.y() - origin_m.y()) / cell_size_m)));
  }
  Eigen::Vector2d CellCenter(int ix, int iy) const {
    return origin_m + cell_size_m * Eigen::Vector2d(ix + 0.5, iy + 0.5);
  }
  std::size_t Count(CellState state) const;
};

}  // namespace objscan::navigation
