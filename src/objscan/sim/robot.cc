#include "objscan/sim/robot.h"

#include <cmath>
#include <limits>

#include "objscan/common/error.h"

namespace objscan::sim {

using platform::ReachStatus;

namespace {

bool SameArm(const ArmSetting& a, const ArmSetting& b) {
  constexpr double kTol = 1e-9;
  return (a.camera_offset_base_m - b.camera_offset_base_m).norm() < kTol &&
         std::abs(a.camera_height_m - b.camera_height_m) < kTol &&
         std::abs(geometry::WrapAngle(a.yaw_rel_rad - b.yaw_rel_rad)) < kTol && std::abs(a.pitch_rad - b.pitch_rad) < kTol;
}

}  // namespace

Robot::Robot(const platform::RobotOptions& options, const platform::BasePose& start, const ArmSetting& arm)
    : options_(options), base_(start), arm_(arm) {
  options_.Validate();
  if (!start.xy_m.allFinite() || !std::isfinite(start.theta_rad)) throw InputError("robot: start pose is not finite");
}

geometry::Pose3 Robot::CameraPoseOf(const platform::BasePose& base, const ArmSetting& arm) {
  const double c = std::cos(base.theta_rad), s = std::sin(base.theta_rad);
  const Eigen::Vector2d offset_world(c * arm.camera_offset_base_m.x() - s * arm.camera_offset_base_m.y(),
                                     s * arm.camera_offset_base_m.x() + c * arm.camera_offset_base_m.y());
  const Eigen::Vector2d xy = base.xy_m + offset_world;
  return geometry::CameraPoseFromYawPitch(Eigen::Vector3d(xy.x(), xy.y(), arm.camera_height_m),
                                          base.theta_rad + arm.yaw_rel_rad, arm.pitch_rad);
}

ReachStatus Robot::CheckCameraPose(const geometry::Pose3& T_world_camera) const {
  if (!T_world_camera.matrix().allFinite()) throw InputError("robot: wanted camera pose is not finite");
  const double z = T_world_camera.translation().z();
  if (z < options_.min_camera_height_m || z > options_.max_camera_height_m) return ReachStatus::kCameraHeightOutOfRange;
  double yaw, pitch;
  geometry::YawPitchOfCamera(T_world_camera, &yaw, &pitch);
  const double pitch_deg = geometry::RadToDeg(pitch);
  // A hair of slack so poses built exactly at the limit pass despite rounding.
  if (pitch_deg < options_.min_pitch_deg - 1e-9 || pitch_deg > options_.max_pitch_deg + 1e-9) {
    return ReachStatus::kPitchOutOfRange;
  }
  return ReachStatus::kOk;
}

double Robot::TravelTime(const navigation::Path2D& path, double theta_start_rad, bool arm_moves, double* theta_end_rad,
                         double* turn_rad) const {
  double theta = theta_start_rad, turn = 0.0, length = 0.0;
  for (std::size_t i = 1; i < path.waypoints.size(); ++i) {
    const Eigen::Vector2d d = path.waypoints[i] - path.waypoints[i - 1];
    const double segment = d.norm();
    if (segment < 1e-9) continue;
    const double heading = std::atan2(d.y(), d.x());
    turn += std::abs(geometry::WrapAngle(heading - theta));
    theta = heading;
    length += segment;
  }
  if (theta_end_rad) *theta_end_rad = theta;
  if (turn_rad) *turn_rad = turn;
  return length / options_.speed_m_per_s + geometry::RadToDeg(turn) / options_.turn_rate_deg_per_s +
         (arm_moves ? options_.arm_move_s : 0.0);
}

ReachPlan Robot::PlanTo(const geometry::Pose3& T_world_camera, const navigation::Navigator& navigator) const {
  ReachPlan plan;
  plan.status = CheckCameraPose(T_world_camera);
  if (!plan.ok()) return plan;
  double yaw, pitch;
  geometry::YawPitchOfCamera(T_world_camera, &yaw, &pitch);
  const Eigen::Vector3d camera = T_world_camera.translation();
  const Eigen::Vector2d camera_xy = camera.head<2>();
  Eigen::Vector2d start_xy;
  std::vector<Eigen::Vector2d> escape_via;
  if (!navigator.StartFrom(base_.xy_m, &start_xy, &escape_via)) {  // a blocked start may back out to a free cell
    plan.status = ReachStatus::kStartBlocked;
    return plan;
  }

  // Candidates: the current base when it already reaches, then rings around the camera, each ring
  // starting straight behind the camera.
  std::vector<Eigen::Vector2d> candidates;
  if ((base_.xy_m - camera_xy).norm() <= options_.max_reach_m) candidates.push_back(base_.xy_m);
  const int rings = static_cast<int>(std::floor(options_.max_reach_m / options_.base_search_step_m + 1e-9));
  for (int ring = 0; ring <= rings; ++ring) {
    const double r = ring * options_.base_search_step_m;
    const int n = ring == 0 ? 1 : options_.base_search_directions;
    for (int k = 0; k < n; ++k) {
      const double a = yaw + M_PI + 2.0 * M_PI * k / n;
      candidates.push_back(camera_xy + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
  }
  bool any_free = false;
  // From where the robot can start (its own cell, or the free cell a blocked start backs out to):
  // searching from a blocked cell reaches nothing.
  double escape_m = 0.0;
  Eigen::Vector2d escape_from = base_.xy_m;
  for (const Eigen::Vector2d& p : escape_via) {
    escape_m += (p - escape_from).norm();
    escape_from = p;
  }
  escape_m += (start_xy - escape_from).norm();
  std::vector<double> path_cost = navigator.PathCosts(start_xy, candidates);
  for (double& c : path_cost) c += escape_m;
  double best_cost = std::numeric_limits<double>::infinity();
  Eigen::Vector2d best_xy = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Eigen::Vector2d& xy = candidates[k];
    if (!navigator.IsFree(xy)) continue;
    any_free = true;
    const bool here = (xy - base_.xy_m).norm() < 1e-12;
    const double cost = here ? 0.0 : path_cost[k];
    if (cost < best_cost) {
      best_cost = cost;
      best_xy = xy;
    }
  }
  if (!any_free) {
    plan.status = ReachStatus::kNoFreeBase;
    return plan;
  }
  if (!std::isfinite(best_cost)) {
    plan.status = ReachStatus::kUnreachable;
    return plan;
  }
  if ((best_xy - base_.xy_m).norm() < 1e-12) {
    plan.path.status = navigation::PlanStatus::kReached;
    plan.path.waypoints = {base_.xy_m, base_.xy_m};
  } else {
    plan.path = navigator.Plan(base_.xy_m, best_xy);
    if (!plan.path.ok()) {  // cannot happen when the distance field reached it, but stay honest
      plan.status = ReachStatus::kUnreachable;
      return plan;
    }
  }

  plan.base.xy_m = best_xy;
  const Eigen::Vector2d offset_world = camera_xy - best_xy;
  double theta_end = base_.theta_rad, turn = 0.0;
  TravelTime(plan.path, base_.theta_rad, false, &theta_end, &turn);
  plan.base.theta_rad = theta_end;
  const double c = std::cos(theta_end), s = std::sin(theta_end);
  plan.arm.camera_offset_base_m = Eigen::Vector2d(c * offset_world.x() + s * offset_world.y(),
                                                  -s * offset_world.x() + c * offset_world.y());
  plan.arm.camera_height_m = camera.z();
  plan.arm.yaw_rel_rad = geometry::WrapAngle(yaw - theta_end);
  plan.arm.pitch_rad = pitch;
  plan.time_s = TravelTime(plan.path, base_.theta_rad, !SameArm(plan.arm, arm_), nullptr, nullptr);
  plan.T_world_camera = CameraPoseOf(plan.base, plan.arm);
  plan.status = ReachStatus::kOk;
  return plan;
}

void Robot::Execute(const ReachPlan& plan) {
  if (!plan.ok()) return;
  double turn = 0.0;
  TravelTime(plan.path, base_.theta_rad, false, nullptr, &turn);
  travel_.distance_m += plan.path.length_m;
  travel_.time_s += plan.time_s;
  travel_.turn_rad += turn;
  travel_.moves += 1;
  if (!SameArm(plan.arm, arm_)) travel_.arm_moves += 1;
  base_ = plan.base;
  arm_ = plan.arm;
}

ReachPlan Robot::MoveTo(const geometry::Pose3& T_world_camera, const navigation::Navigator& navigator) {
  ReachPlan plan = PlanTo(T_world_camera, navigator);
  Execute(plan);
  return plan;
}

}  // namespace objscan::sim
