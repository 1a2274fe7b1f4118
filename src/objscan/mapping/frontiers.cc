#include "objscan/mapping/frontiers.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace objscan::mapping {

void FrontierOptions::Validate() const {
  config::RequireInRange("cell_size_m", cell_size_m, 0.005, 1.0);
  config::RequireInRange("min_floor_elements_per_cell", min_floor_elements_per_cell, 1, 1000000);
  config::RequireInRange("min_cluster_cells", min_cluster_cells, 1, 1000000);
  config::RequireNonNegative("wall_margin_m", wall_margin_m);
  config::RequireInRange("obstacle_clearance_cells", obstacle_clearance_cells, 0, 100);
  config::RequireNonNegative("obstacle_probe_height_m", obstacle_probe_height_m);
}

std::vector<FrontierGoal> FindFloorFrontiers(const SurfaceMap& surface, const OccupancyMap& occupancy,
                                             const StructureResult& structure, const FrontierOptions& options) {
  options.Validate();
  std::vector<FrontierGoal> goals;
  if (!structure.has_floor) return goals;
  const double cell = options.cell_size_m;

  // Dense grid over the floor elements' footprint plus a one-cell rim.
  int x0 = INT_MAX, y0 = INT_MAX, x1 = INT_MIN, y1 = INT_MIN;
  std::vector<std::pair<int, int>> floor_cells;
  for (std::size_t i = 0; i < surface.size(); ++i) {
    if (surface.structure(i) != Structure::kFloor) continue;
    const Eigen::Vector3f& p = surface.position(i);
    const int ix = static_cast<int>(std::floor(p.x() / cell));
    const int iy = static_cast<int>(std::floor(p.y() / cell));
    floor_cells.emplace_back(ix, iy);
    x0 = std::min(x0, ix);
    y0 = std::min(y0, iy);
    x1 = std::max(x1, ix);
    y1 = std::max(y1, iy);
  }
  if (floor_cells.empty()) return goals;
  // A one-cell rim for the unexplored neighbours, plus room for their obstacle neighbourhoods.
  const int rim = 1 + options.obstacle_clearance_cells;
  x0 -= rim;
  y0 -= rim;
  x1 += rim;
  y1 += rim;
  const int w = x1 - x0 + 1, h = y1 - y0 + 1;
  auto idx = [&](int ix, int iy) { return static_cast<std::size_t>(iy - y0) * w + (ix - x0); };
  std::vector<int> count(static_cast<std::size_t>(w) * h, 0);
  for (const auto& c : floor_cells) ++count[idx(c.first, c.second)];
  auto center = [&](int ix, int iy) { return Eigen::Vector2d((ix + 0.5) * cell, (iy + 0.5) * cell); };
  auto observed = [&](int ix, int iy) {
    return ix >= x0 && ix <= x1 && iy >= y0 && iy <= y1 && count[idx(ix, iy)] >= options.min_floor_elements_per_cell;
  };
  const double probe_z = structure.floor_height_m + 1.5 * occupancy.resolution_m();
  // Per cell, lazily: 0 = not yet probed, 1 = clear, 2 = an occupied voxel in the obstacle band.
  std::vector<std::uint8_t> obstacle(count.size(), 0);
  auto has_obstacle = [&](int ix, int iy) {
    std::uint8_t& o = obstacle[idx(ix, iy)];
    if (o == 0) {
      o = 1;
      const Eigen::Vector2d c = center(ix, iy);
      const double top = structure.floor_height_m + options.obstacle_probe_height_m;
      for (double z = probe_z; z <= top + 1e-9; z += occupancy.resolution_m()) {
        if (occupancy.Query(Eigen::Vector3d(c.x(), c.y(), z)) == Occupancy::kOccupied) {
          o = 2;
          break;
        }
      }
    }
    return o == 2;
  };
  const int clearance = options.obstacle_clearance_cells;
  auto unexplored = [&](int ix, int iy) {
    if (observed(ix, iy)) return false;
    const Eigen::Vector2d c = center(ix, iy);
    // Cells beyond a wall plane are outside the room: nothing to explore there.
    if (!structure.InsideWalls(Eigen::Vector3d(c.x(), c.y(), probe_z), 0.0)) return false;
    if (occupancy.Query(Eigen::Vector3d(c.x(), c.y(), probe_z)) != Occupancy::kUnknown) return false;
    for (int dy = -clearance; dy <= clearance; ++dy) {
      for (int dx = -clearance; dx <= clearance; ++dx) {
        if (has_obstacle(ix + dx, iy + dy)) return false;
      }
    }
    return true;
  };

  std::vector<std::uint8_t> frontier(count.size(), 0);
  static const int kN4[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (int iy = y0 + clearance; iy <= y1 - clearance; ++iy) {
    for (int ix = x0 + clearance; ix <= x1 - clearance; ++ix) {
      if (!observed(ix, iy)) continue;
      const Eigen::Vector2d c = center(ix, iy);
      if (!structure.InsideWalls(Eigen::Vector3d(c.x(), c.y(), probe_z), options.wall_margin_m)) continue;
      // An obstacle surface right above this cell (e.g. the side of furniture falling into this
      // cell's voxel) hides what lies beyond: its unknown interior is no frontier.
      if (occupancy.Query(Eigen::Vector3d(c.x(), c.y(), probe_z)) == Occupancy::kOccupied) continue;
      for (const auto& d : kN4) {
        if (unexplored(ix + d[0], iy + d[1])) {
          frontier[idx(ix, iy)] = 1;
          break;
        }
      }
    }
  }

  // 8-connected clusters.
  std::vector<std::uint8_t> visited(count.size(), 0);
  std::vector<std::pair<int, int>> stack;
  for (int iy = y0; iy <= y1; ++iy) {
    for (int ix = x0; ix <= x1; ++ix) {
      if (!frontier[idx(ix, iy)] || visited[idx(ix, iy)]) continue;
      FrontierGoal goal;
      stack.assign(1, {ix, iy});
      visited[idx(ix, iy)] = 1;
      while (!stack.empty()) {
        const auto [cx, cy] = stack.back();
        stack.pop_back();
        goal.cells_m.push_back(center(cx, cy));
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = cx + dx, ny = cy + dy;
            if (nx < x0 || nx > x1 || ny < y0 || ny > y1) continue;
            const std::size_t k = idx(nx, ny);
            if (frontier[k] && !visited[k]) {
              visited[k] = 1;
              stack.emplace_back(nx, ny);
            }
          }
        }
      }
      goal.size_cells = static_cast<int>(goal.cells_m.size());
      if (goal.size_cells < options.min_cluster_cells) continue;
      for (const auto& c : goal.cells_m) goal.centroid_m += c;
      goal.centroid_m /= goal.size_cells;
      goals.push_back(std::move(goal));
    }
  }
  std::stable_sort(goals.begin(), goals.end(),
                   [](const FrontierGoal& a, const FrontierGoal& b) { return a.size_cells > b.size_cells; });
  return goals;
}

}  // namespace objscan::mapping
