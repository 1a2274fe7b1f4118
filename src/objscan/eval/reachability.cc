#include "objscan/eval/reachability.h"

#include <cmath>

#include "objscan/common/config.h"
#include "objscan/sim/ground_truth_occupancy.h"

namespace objscan::eval {

RoomReachability ReachableRooms(const world::Scene& scene, const RoomPartition& rooms, const Eigen::Vector2d& start_xy_m,
                                const RoomReachabilityOptions& options) {
  config::RequirePositive("reachability.robot_radius_m", options.robot_radius_m);
  config::RequirePositive("reachability.robot_height_m", options.robot_height_m);
  config::RequireNonNegative("reachability.min_reachable_area_m2", options.min_reachable_area_m2);
  config::RequireNonNegative("reachability.start_search_m", options.start_search_m);
  options.navigation.Validate();
  RoomReachability out;
  if (rooms.rooms().empty()) return out;
  const sim::GroundTruthOccupancy truth(scene);
  const navigation::Navigator navigator(truth, options.robot_radius_m, options.robot_height_m, options.navigation);
  Eigen::Vector2d start;
  if (!navigator.NearestFree(start_xy_m, options.start_search_m, &start)) return out;
  const std::vector<double> distance_m = navigator.DistanceField(start);
  const navigation::OccupancyGrid2D& grid = navigator.grid();
  const double cell_m2 = grid.cell_size_m * grid.cell_size_m;
  out.known = true;
  out.reachable_area_m2.assign(rooms.rooms().size(), 0.0);
  for (int iy = 0; iy < grid.height; ++iy) {
    for (int ix = 0; ix < grid.width; ++ix) {
      if (!std::isfinite(distance_m[grid.Index(ix, iy)])) continue;
      const Eigen::Vector2d xy = grid.CellCenter(ix, iy);
      const int room = rooms.RoomAt(xy.x(), xy.y(), 0.0);
      if (room >= 0) out.reachable_area_m2[static_cast<std::size_t>(room)] += cell_m2;
    }
  }
  out.reachable.resize(rooms.rooms().size());
  for (std::size_t r = 0; r < out.reachable.size(); ++r) {
    out.reachable[r] = out.reachable_area_m2[r] >= options.min_reachable_area_m2 ? 1 : 0;
  }
  return out;
}

}  // namespace objscan::eval
