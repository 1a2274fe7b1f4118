#pragma once
// The simulated robot: a disk-shaped mobile base (x, y, theta) carrying the depth camera on an arm.
// The arm places the camera anywhere within reach of the base centre, at a height and pitch within
// limits, with any yaw relative to the base (no roll). Moving to a wanted camera pose means finding a
// base pose on free floor from which the arm reaches it, driving there and setting the arm; the
// travel (distance and simulated time) is accounted here and reported as navigate_sim. The body's
// dimensions and limits are platform::RobotOptions; simulated_robot.h makes it a platform::Platform.
#include <Eigen/Core>

#include "objscan/geometry/pose.h"
#include "objscan/navigation/navigator.h"
#include "objscan/platform/platform.h"
#include "objscan/platform/robot_options.h"

namespace objscan::sim {

struct ArmSetting {
  Eigen::Vector2d camera_offset_base_m = Eigen::Vector2d::Zero();  // camera XY in the base frame
  double camera_height_m = 1.0;                                    // above the floor
  double yaw_rel_rad = 0.0;                                        // camera yaw relative to the base heading
  double pitch_rad = 0.0;                                          // positive looks up
};

struct ReachPlan {
  platform::ReachStatus status = platform::ReachStatus::kUnreachable;
  platform::BasePose base;  // where the base ends up
  ArmSetting arm;
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();  // the camera pose reached (roll-free)
  navigation::Path2D path;  // base path from the current position
  double time_s = 0.0;      // simulated time the move takes
  bool ok() const { return status == platform::ReachStatus::kOk; }
};

class Robot {
 public:
  Robot(const platform::RobotOptions& options, const platform::BasePose& start, const ArmSetting& arm = ArmSetting());

  const platform::RobotOptions& options() const { return options_; }
  const platform::BasePose& base() const { return base_; }
  const ArmSetting& arm() const { return arm_; }
  const platform::TravelStats& travel() const { return travel_; }
  geometry::Pose3 CameraPose() const { return CameraPoseOf(base_, arm_); }
  static geometry::Pose3 CameraPoseOf(const platform::BasePose& base, const ArmSetting& arm);

  // Checks the arm limits for a camera pose (the roll of the wanted pose is dropped).
  platform::ReachStatus CheckCameraPose(const geometry::Pose3& T_world_camera) const;

  // Plans a move to the wanted camera pose without executing it: the reachable base position (free
  // on the navigator's grid, within reach of the camera) with the shortest path, ties broken by
  // search order (nearer the camera first, then behind it).
  ReachPlan PlanTo(const geometry::Pose3& T_world_camera, const navigation::Navigator& navigator) const;
  // Executes a plan from PlanTo (kOk only; otherwise nothing happens): moves, accounts the travel.
  void Execute(const ReachPlan& plan);
  // PlanTo then Execute.
  ReachPlan MoveTo(const geometry::Pose3& T_world_camera, const navigation::Navigator& navigator);

  // Simulated time of driving along `path` starting with heading theta_start, ending heading along
  // the last segment (turns in place, then straight lines), plus one arm move when arm_moves.
  double TravelTime(const navigation::Path2D& path, double theta_start_rad, bool arm_moves, double* theta_end_rad,
                    double* turn_rad) const;

 private:
  platform::RobotOptions options_;
  platform::BasePose base_;
  ArmSetting arm_;
  platform::TravelStats travel_;
};

}  // namespace objscan::sim
