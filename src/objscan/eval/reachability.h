#pragma once
// Which rooms of a scene (rooms.h) the robot can drive into from where it started, on the
// ground-truth floor plan: the robot's disk moved over the ground-truth occupancy (sim/
// ground_truth_occupancy.h) as the navigator moves it. A room behind a closed door is unreachable:
// its objects are listed apart and the metrics are also given over the reachable ones (a run cannot
// be blamed for them). Ground truth only: the scanner never sees this.
#include <Eigen/Core>
#include <vector>

#include "objscan/eval/rooms.h"
#include "objscan/navigation/navigator.h"
#include "objscan/world/scene.h"

namespace objscan::eval {

struct RoomReachabilityOptions {
  double robot_radius_m = 0.25;
  double robot_height_m = 1.8;
  navigation::NavigatorOptions navigation;
  // A room counts as reachable when the robot's centre can reach at least this much of its floor
  // (a doorway's threshold is not the room).
  double min_reachable_area_m2 = 0.25;
  // The start is moved to the nearest free spot within this distance (the robot's own map and the
  // ground truth may disagree by a cell about where it stands).
  double start_search_m = 0.5;
};

struct RoomReachability {
  bool known = false;                    // false: no room, or no free floor at the start (all count as reachable)
  std::vector<char> reachable;           // per room of the partition
  std::vector<double> reachable_area_m2; // per room: floor the robot's centre can reach
  bool Reachable(int room) const {
    return !known || room < 0 || room >= static_cast<int>(reachable.size()) || reachable[room] != 0;
  }
};

// Throws InputError for invalid options.
RoomReachability ReachableRooms(const world::Scene& scene, const RoomPartition& rooms, const Eigen::Vector2d& start_xy_m,
                                const RoomReachabilityOptions& options = RoomReachabilityOptions());

}  // namespace objscan::eval
