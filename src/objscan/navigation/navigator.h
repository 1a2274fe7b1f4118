#pragma once
// Navigation of the robot's base on a 2-D occupancy grid: obstacles and unknown cells inflated by the
// robot's footprint, A* (8-connected, octile heuristic, no corner cutting), then line-of-sight path
// smoothing on the inflated grid. Expected outcomes (no path, blocked start or goal) are statuses.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/navigation/occupancy_source.h"

namespace objscan::navigation {

struct NavigatorOptions {
  double cell_size_m = 0.05;
  double min_obstacle_height_m = 0.02;  // anything lower (rugs, the floor itself) is drivable
  bool smooth_path = true;              // line-of-sight shortcuts over the A* cell path
  // A start that has become blocked (an obstacle seen after the robot got there, now within its
  // inflation radius) is left by the shortest straight move of at most this length to a free cell;
  // 0 = a blocked start is kStartBlocked.
  double start_escape_m = 0.3;
  // When no free cell is that near (a robot wedged between furniture it saw only once there, or
  // standing on floor its camera never saw), it leaves along the shortest route of at most this
  // length through cells not seen occupied (blocked only by inflation or unknown) to a free cell: it
  // came in that way. 0 = no route (such a start is kStartBlocked).
  double start_escape_route_m = 1.0;

  template <class V>
  void Visit(V& v) {
    v("cell_size_m", cell_size_m);
    v("min_obstacle_height_m", min_obstacle_height_m);
    v("smooth_path", smooth_path);
    v("start_escape_m", start_escape_m);
    v("start_escape_route_m", start_escape_route_m);
  }
  void Validate() const;
};

enum class PlanStatus {
  kReached,      // a path was found (possibly of zero length)
  kStartBlocked, // the start position is not free for the robot (obstacle, unknown, off the grid)
  kGoalBlocked,  // the goal position is not free for the robot
  kUnreachable,  // both are free but no path connects them
};
const char* PlanStatusName(PlanStatus status);

struct Path2D {
  PlanStatus status = PlanStatus::kUnreachable;
  std::vector<Eigen::Vector2d> waypoints;  // world XY, start first and goal last (when reached)
  double length_m = 0.0;                   // along the waypoints
  double grid_length_m = 0.0;              // of the A* cell path before smoothing
  int expansions = 0;                      // A* nodes expanded
  bool ok() const { return status == PlanStatus::kReached; }
};

class Navigator {
 public:
  // The robot is a vertical cylinder (radius, height); the grid is taken from `source` for the band
  // (min_obstacle_height_m, robot_height_m).
  Navigator(const OccupancySource& source, double robot_radius_m, double robot_height_m,
            const NavigatorOptions& options = NavigatorOptions());

  // Takes a fresh grid from the source (after the map changed).
  void Update(const OccupancySource& source);

  const NavigatorOptions& options() const { return options_; }
  // The grid as the source gave it, and the inflated one the robot's centre moves on (1 = blocked).
  const OccupancyGrid2D& grid() const { return grid_; }
  const std::vector<std::uint8_t>& blocked() const { return blocked_; }
  // Blocked cells lie within robot_radius + half a cell diagonal of an occupied or unknown cell, so
  // every point of a free cell is a valid position for the robot's centre.
  double inflation_radius_m() const { return inflation_radius_m_; }

  // Whether the robot's centre may be at xy.
  bool IsFree(const Eigen::Vector2d& xy) const;
  // Whether the robot's centre can move straight from a to b (every cell the segment touches is free).
  bool LineOfSight(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

  Path2D Plan(const Eigen::Vector2d& start, const Eigen::Vector2d& goal) const;

  // Where a robot at xy starts moving from: xy itself when free, else the nearest free cell within
  // options().start_escape_m, else the end of EscapeRoute. False when none exists (a plan from xy is
  // kStartBlocked). `via` (optional) receives the route's waypoints before the start (empty for xy
  // itself and for a straight escape).
  bool StartFrom(const Eigen::Vector2d& xy, Eigen::Vector2d* start_xy, std::vector<Eigen::Vector2d>* via = nullptr) const;

  // The shortest 8-connected route from xy's cell through cells not seen occupied (free, inflated or
  // unknown) to the nearest free cell, at most max_m long: the cell centres after xy's cell, the free
  // one last. Empty when there is none (or xy's own cell is occupied or outside the grid).
  std::vector<Eigen::Vector2d> EscapeRoute(const Eigen::Vector2d& xy, double max_m) const;

  // Grid path length (metres, 8-connected, same moves as A*) from start to every cell; infinity where
  // unreachable; all infinity when start is not free. Index as grid().Index(ix, iy).
  std::vector<double> DistanceField(const Eigen::Vector2d& start) const;

  // Grid path length from start to each target (infinity when unreachable or not free), by a
  // Dijkstra search that stops once every reachable target is settled. Same values as DistanceField.
  std::vector<double> PathCosts(const Eigen::Vector2d& start, const std::vector<Eigen::Vector2d>& targets) const;

  // The free position nearest to xy (cell centre, or xy itself when free) within max_distance_m.
  bool NearestFree(const Eigen::Vector2d& xy, double max_distance_m, Eigen::Vector2d* free_xy) const;

 private:
  bool CellFree(int ix, int iy) const {
    return grid_.Contains(ix, iy) && blocked_[grid_.Index(ix, iy)] == 0;
  }
  void Inflate();
  // Dijkstra from start; stops early once `remaining_targets` marked cells (target[i] != 0) are
  // settled (pass 0 and an empty mask for the full field). Costs in cells.
  std::vector<double> Dijkstra(const Eigen::Vector2d& start, const std::vector<std::uint8_t>& target,
                               int remaining_targets) const;
  std::vector<Eigen::Vector2d> Smooth(const std::vector<Eigen::Vector2d>& points) const;

  NavigatorOptions options_;
  double robot_radius_m_;
  double robot_height_m_;
  double inflation_radius_m_ = 0.0;
  OccupancyGrid2D grid_;
  std::vector<std::uint8_t> blocked_;
};

}  // namespace objscan::navigation
