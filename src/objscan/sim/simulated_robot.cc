#include "objscan/sim/simulated_robot.h"

#include "objscan/sim/start_pose.h"

namespace objscan::sim {

SimulatedRobot::SimulatedRobot(const world::Scene& scene, const render::SensorOptions& sensor,
                               const platform::RobotOptions& robot, const platform::BasePose& start, std::uint64_t seed)
    : scene_(scene), camera_(scene, sensor), robot_(robot, start), rng_(DeriveSeed(seed, 0x5343414eull)) {}

// The camera first: a scene without triangles is reported as such, not as one without floor.
SimulatedRobot::SimulatedRobot(const world::Scene& scene, const render::SensorOptions& sensor,
                               const platform::RobotOptions& robot, const navigation::NavigatorOptions& navigation,
                               std::uint64_t seed)
    : scene_(scene),
      camera_(scene, sensor),
      robot_(robot, ChooseStartPose(scene, robot, navigation)),
      rng_(DeriveSeed(seed, 0x5343414eull)) {}

platform::DepthFrame SimulatedRobot::Capture() { return camera_.Render(robot_.CameraPose(), &rng_); }

platform::ReachStatus SimulatedRobot::CheckReach(const geometry::Pose3& T_world_camera,
                                                 const navigation::Navigator& map) const {
  return robot_.PlanTo(T_world_camera, map).status;
}

platform::Move SimulatedRobot::MoveCamera(const geometry::Pose3& T_world_camera, const navigation::Navigator& map) {
  const ReachPlan plan = robot_.MoveTo(T_world_camera, map);
  platform::Move move;
  move.status = plan.status;
  if (!plan.ok()) return move;
  move.path = plan.path;
  move.T_world_camera = plan.T_world_camera;
  return move;
}

geometry::Pose3 SimulatedRobot::TurnCamera(const geometry::Pose3& T_world_camera) {
  // The camera straight above the base centre, turned by the arm alone: one arm move, no driving.
  ReachPlan plan;
  plan.status = platform::ReachStatus::kOk;
  plan.base = robot_.base();
  double yaw = 0.0, pitch = 0.0;
  geometry::YawPitchOfCamera(T_world_camera, &yaw, &pitch);
  plan.arm = robot_.arm();
  plan.arm.camera_offset_base_m.setZero();
  plan.arm.camera_height_m = T_world_camera.translation().z();
  plan.arm.yaw_rel_rad = geometry::WrapAngle(yaw - plan.base.theta_rad);
  plan.arm.pitch_rad = pitch;
  plan.T_world_camera = Robot::CameraPoseOf(plan.base, plan.arm);
  plan.path.status = navigation::PlanStatus::kReached;
  plan.path.waypoints = {robot_.base().xy_m};
  plan.time_s = robot_.options().arm_move_s;
  robot_.Execute(plan);
  return robot_.CameraPose();
}

}  // namespace objscan::sim
