#pragma once
// The rooms of a scene, for per-room metrics of a run through several rooms (a house): the floor
// seen from above, cut by walls and doors and split at openings narrower than a doorway (the free
// floor eroded by half a doorway falls apart into room cores; each free cell joins the nearest
// core). Ground truth only: the scanner never sees this.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "objscan/world/scene.h"

namespace objscan::eval {

struct RoomPartitionOptions {
  double cell_m = 0.1;
  // Wall and door triangles block a cell where they pass between these heights above the floor
  // (skirting boards and lintels do not).
  double blocking_min_z_m = 0.3;
  double blocking_max_z_m = 1.8;
  double min_room_area_m2 = 2.0;  // smaller regions (gaps behind furniture, wall cavities) are no room
  // Openings narrower than this separate rooms (doorways without a door, gaps in folding doors):
  // rooms grow from the floor at least half of it away from walls and doors (a morphological split).
  double doorway_width_m = 1.0;
  // Only the floor within this margin of the furniture's bounds is partitioned (a Gazebo ground
  // plane can be 100 m wide).
  double margin_m = 1.0;
};

struct Room {
  int id = 0;                              // 0, 1, ... by decreasing area
  double area_m2 = 0.0;
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();  // centroid of its cells
};

class RoomPartition {
 public:
  // Throws InputError for invalid options. A scene without floor triangles has no room.
  static RoomPartition FromScene(const world::Scene& scene, const RoomPartitionOptions& options = {});

  const std::vector<Room>& rooms() const { return rooms_; }
  // The room at (x, y); else the room of the nearest room cell within search_m (a window or door
  // stands in the wall between rooms); -1 when there is none.
  int RoomAt(double x_m, double y_m, double search_m = 0.5) const;
  // Every room with a cell within search_m of (x, y), ascending (a window in the wall between two
  // rooms is near both).
  std::vector<int> RoomsWithin(double x_m, double y_m, double search_m) const;

 private:
  int CellRoom(int ix, int iy) const;
  std::vector<Room> rooms_;
  std::vector<int> cell_room_;  // -1: no room
  Eigen::Vector2d origin_m_ = Eigen::Vector2d::Zero();
  double cell_m_ = 0.1;
  int nx_ = 0, ny_ = 0;
};

}  // namespace objscan::eval
