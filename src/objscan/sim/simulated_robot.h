#pragma once
// objscan's simulator as a platform: the robot of robot.h put down in a world::Scene, its frames
// rendered by render::DepthCamera (with Kinect-style noise drawn from a generator seeded per run).
#include <cstdint>
#include <string>

#include "objscan/common/rng.h"
#include "objscan/platform/platform.h"
#include "objscan/platform/robot_options.h"
#include "objscan/render/depth_camera.h"
#include "objscan/sim/robot.h"
#include "objscan/world/scene.h"

namespace objscan::sim {

class SimulatedRobot : public platform::Platform {
 public:
  // Puts the robot down at `start` (start_pose.h chooses one as an operator would). `scene` must
  // outlive the robot. Throws InputError when the scene has no triangles or the start is not finite.
  SimulatedRobot(const world::Scene& scene, const render::SensorOptions& sensor, const platform::RobotOptions& robot,
                 const platform::BasePose& start, std::uint64_t seed);
  // Puts the robot down where an operator would (ChooseStartPose: it reads the scene, as an operator
  // sees the room). Throws InputError when the scene has no free floor to start on.
  SimulatedRobot(const world::Scene& scene, const render::SensorOptions& sensor, const platform::RobotOptions& robot,
                 const navigation::NavigatorOptions& navigation, std::uint64_t seed);

  std::string world_name() const override { return scene_.name(); }
  platform::CameraIntrinsics intrinsics() const override { return camera_.options().Intrinsics(); }
  platform::BasePose base() const override { return robot_.base(); }
  geometry::Pose3 T_world_camera() const override { return robot_.CameraPose(); }
  platform::TravelStats travel() const override { return robot_.travel(); }
  platform::DepthFrame Capture() override;
  platform::ReachStatus CheckReach(const geometry::Pose3& T_world_camera,
                                   const navigation::Navigator& map) const override;
  platform::Move MoveCamera(const geometry::Pose3& T_world_camera, const navigation::Navigator& map) override;
  geometry::Pose3 TurnCamera(const geometry::Pose3& T_world_camera) override;

  const Robot& robot() const { return robot_; }
  const render::DepthCamera& camera() const { return camera_; }

 private:
  const world::Scene& scene_;
  render::DepthCamera camera_;
  Robot robot_;
  Rng rng_;  // sensor noise
};

}  // namespace objscan::sim
