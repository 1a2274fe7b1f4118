#pragma once
// The simulated robot: a disk-shaped mobile base (x, y, theta) carrying the depth camera on an arm.
// The arm places the camera anywhere within reach of the base centre, at a height and pitch within
// limits, with any yaw relative to the base (no roll). Moving to a wanted camera pose means finding a
// base pose on free floor from which the arm reaches it, driving there and setting the arm; the
// travel (distance and simulated time) is accounted here and reported as navigate_sim.
#include <Eigen/Core>

#include "objscan/common/config.h"
#include "objscan/geometry/pose.h"
#include "objscan/sim/navigator.h"

namespace objscan::sim {

struct RobotOptions {
  double base_radius_m = 0.25;
  double height_m = 1.8;             // the body (base and mast) is a cylinder this tall for navigation
  double min_camera_height_m = 0.3;
  double max_camera_height_m = 1.8;
  double min_pitch_deg = -70.0;
  double max_pitch_deg = 30.0;
  double max_reach_m = 0.6;          // camera within this horizontal distance of the base centre
  double speed_m_per_s = 0.3;
  double turn_rate_deg_per_s = 30.0;
  double arm_move_s = 2.0;           // per change of the arm setting
  double base_search_step_m = 0.1;   // candidate base positions: rings this far apart around the camera
  int base_search_directions = 24;   // ... with this many positions per ring

  template <class V>
  void Visit(V& v) {
    v("base_radius_m", base_radius_m);
    v("height_m", height_m);
    v("min_camera_height_m", min_camera_height_m);
    v("max_camera_height_m", max_camera_height_m);
    v("min_pitch_deg", min_pitch_deg);
    v("max_pitch_deg", max_pitch_deg);
    v("max_reach_m", max_reach_m);
    v("speed_m_per_s", speed_m_per_s);
    v("turn_rate_deg_per_s", turn_rate_deg_per_s);
    v("arm_move_s", arm_move_s);
    v("base_search_step_m", base_search_step_m);
    v("base_search_directions", base_search_directions);
  }
  void Validate() const;
};

struct BasePose {
  Eigen::Vector2d xy_m = Eigen::Vector2d::Zero();
  double theta_rad = 0.0;  // heading about world Z, 0 = +X
};

struct ArmSetting {
  Eigen::Vector2d camera_offset_base_m = Eigen::Vector2d::Zero();  // camera XY in the base frame
  double camera_height_m = 1.0;                                    // above the floor
  double yaw_rel_rad = 0.0;                                        // camera yaw relative to the base heading
  double pitch_rad = 0.0;                                          // positive looks up
};

enum class ReachStatus {
  kOk,
  kCameraHeightOutOfRange,  // the wanted camera is too low or too high for the arm
  kPitchOutOfRange,         // the wanted camera looks too far down or up
  kNoFreeBase,              // no free floor within reach of the wanted camera position
  kStartBlocked,            // the robot's current base position is not free on the grid
  kUnreachable,             // free base positions exist but no path leads there
};
const char* ReachStatusName(ReachStatus status);

struct ReachPlan {
  ReachStatus status = ReachStatus::kUnreachable;
  BasePose base;                 // where the base ends up
  ArmSetting arm;
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();  // the camera pose reached (roll-free)
  Path2D path;                   // base path from the current position
  double time_s = 0.0;           // simulated time the move takes
  bool ok() const { return status == ReachStatus::kOk; }
};

struct TravelStats {
  double distance_m = 0.0;
  double time_s = 0.0;  // navigate_sim: driving, turning and arm moves
  double turn_rad = 0.0;
  int moves = 0;        // executed plans
  int arm_moves = 0;
};

class Robot {
 public:
  Robot(const RobotOptions& options, const BasePose& start, const ArmSetting& arm = ArmSetting());

  const RobotOptions& options() const { return options_; }
  const BasePose& base() const { return base_; }
  const ArmSetting& arm() const { return arm_; }
  const TravelStats& travel() const { return travel_; }
  geometry::Pose3 CameraPose() const { return CameraPoseOf(base_, arm_); }
  static geometry::Pose3 CameraPoseOf(const BasePose& base, const ArmSetting& arm);

  // Checks the arm limits for a camera pose (the roll of the wanted pose is dropped).
  ReachStatus CheckCameraPose(const geometry::Pose3& T_world_camera) const;

  // Plans a move to the wanted camera pose without executing it: the reachable base position (free
  // on the navigator's grid, within reach of the camera) with the shortest path, ties broken by
  // search order (nearer the camera first, then behind it).
  ReachPlan PlanTo(const geometry::Pose3& T_world_camera, const Navigator& navigator) const;
  // Executes a plan from PlanTo (kOk only; otherwise nothing happens): moves, accounts the travel.
  void Execute(const ReachPlan& plan);
  // PlanTo then Execute.
  ReachPlan MoveTo(const geometry::Pose3& T_world_camera, const Navigator& navigator);

  // Simulated time of driving along `path` starting with heading theta_start, ending heading along
  // the last segment (turns in place, then straight lines), plus one arm move when arm_moves.
  double TravelTime(const Path2D& path, double theta_start_rad, bool arm_moves, double* theta_end_rad,
                    double* turn_rad) const;

 private:
  RobotOptions options_;
  BasePose base_;
  ArmSetting arm_;
  TravelStats travel_;
};

}  // namespace objscan::sim
