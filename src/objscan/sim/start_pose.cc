#include "objscan/sim/start_pose.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "objscan/common/error.h"
#include "objscan/sim/ground_truth_occupancy.h"

namespace objscan::sim {

platform::BasePose ChooseStartPose(const world::Scene& scene, const platform::RobotOptions& robot_options,
                                   const navigation::NavigatorOptions& navigation_options) {
  // The operator puts the robot down on free floor: the free spot farthest from obstacles, nearest the
  // room's centre on ties.
  const GroundTruthOccupancy truth(scene);
  const navigation::Navigator nav(truth, robot_options.base_radius_m, robot_options.height_m, navigation_options);
  const auto& grid = nav.grid();
  const auto& blocked = nav.blocked();
  std::vector<double> clearance(grid.NumCells(), 0.0);
  // Chamfer distance to the nearest blocked cell (two passes).
  const double inf = 1e9, c1 = grid.cell_size_m, c2 = grid.cell_size_m * std::sqrt(2.0);
  for (std::size_t i = 0; i < clearance.size(); ++i) clearance[i] = blocked[i] ? 0.0 : inf;
  auto relax = [&](int x, int y, int nx, int ny, double w) {
    if (!grid.Contains(nx, ny)) {
      clearance[grid.Index(x, y)] = std::min(clearance[grid.Index(x, y)], w);
      return;
    }
    clearance[grid.Index(x, y)] = std::min(clearance[grid.Index(x, y)], clearance[grid.Index(nx, ny)] + w);
  };
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < grid.width; ++x) {
      relax(x, y, x - 1, y, c1), relax(x, y, x, y - 1, c1), relax(x, y, x - 1, y - 1, c2), relax(x, y, x + 1, y - 1, c2);
    }
  for (int y = grid.height - 1; y >= 0; --y)
    for (int x = grid.width - 1; x >= 0; --x) {
      relax(x, y, x + 1, y, c1), relax(x, y, x, y + 1, c1), relax(x, y, x + 1, y + 1, c2), relax(x, y, x - 1, y + 1, c2);
    }
  const Eigen::Vector3d center =
      scene.FurnitureBounds().Empty() ? scene.Bounds().Center() : scene.FurnitureBounds().Center();
  double best = -1.0;
  platform::BasePose start;
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      const std::size_t i = grid.Index(x, y);
      if (blocked[i]) continue;
      const Eigen::Vector2d xy = grid.CellCenter(x, y);
      // Quantise clearance so that the tie-break towards the centre matters.
      const double score = std::floor(std::min(clearance[i], 1.0) / 0.1) - 1e-3 * (xy - center.head<2>()).norm();
      if (score > best) {
        best = score;
        start.xy_m = xy;
        start.theta_rad = std::atan2(center.y() - xy.y(), center.x() - xy.x());
      }
    }
  }
  if (best < 0.0) throw InputError("scene '" + scene.name() + "': no free floor for the robot to start on");
  return start;
}

}  // namespace objscan::sim
