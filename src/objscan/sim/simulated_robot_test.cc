#include "objscan/sim/simulated_robot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "objscan/common/error.h"
#include "objscan/navigation/navigator.h"
#include "objscan/platform/testing/platform_contract.h"
#include "objscan/sim/ground_truth_occupancy.h"
#include "objscan/sim/start_pose.h"
#include "objscan/sim/test_scenes.h"

namespace objscan::sim {
namespace {

using testing::CabinetRoom;
using testing::Room;
using testing::SmallSensor;

TEST(SimulatedRobotTest, KeepsThePlatformContract) {
  const world::Scene scene = CabinetRoom();
  const platform::RobotOptions options;
  platform::BasePose start;
  start.xy_m = Eigen::Vector2d(1.0, 2.0);
  SimulatedRobot robot(scene, SmallSensor(), options, start, /*seed=*/3);
  const GroundTruthOccupancy truth(scene);
  const navigation::Navigator map(truth, options.base_radius_m, options.height_m);
  const geometry::Pose3 reachable =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(3.5, 2.5, 1.2), -0.5, geometry::DegToRad(-20));
  const geometry::Pose3 too_high =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(3.5, 2.5, options.max_camera_height_m + 0.5), 0.0, 0.0);
  platform::testing::ExpectPlatformContract(&robot, map, reachable, too_high);
  EXPECT_EQ(robot.CheckReach(too_high, map), platform::ReachStatus::kCameraHeightOutOfRange);
  EXPECT_EQ(robot.world_name(), "room");
}

TEST(SimulatedRobotTest, NoiseFollowsTheSeed) {
  const world::Scene scene = CabinetRoom();
  platform::BasePose start;
  start.xy_m = Eigen::Vector2d(1.0, 2.0);
  // The full-size sensor: at the small one's focal length, disparity steps (5 cm at 2 m) swallow the noise.
  const render::SensorOptions sensor;
  SimulatedRobot a(scene, sensor, platform::RobotOptions(), start, 5);
  SimulatedRobot b(scene, sensor, platform::RobotOptions(), start, 5);
  SimulatedRobot c(scene, sensor, platform::RobotOptions(), start, 6);
  const std::vector<float> first = a.Capture().depth_m;
  ASSERT_GT(std::count_if(first.begin(), first.end(), [](float d) { return d > 0.f; }), 1000);
  EXPECT_EQ(first, b.Capture().depth_m);
  EXPECT_NE(first, c.Capture().depth_m);
  EXPECT_NE(first, a.Capture().depth_m);  // the noise goes on, frame after frame
}

TEST(StartPoseTest, AnOperatorPutsTheRobotDownFarthestFromObstaclesFacingTheFurniture) {
  // An empty room: its centre, the farthest point from every wall.
  const platform::RobotOptions robot;
  const navigation::NavigatorOptions navigation;
  const platform::BasePose empty = ChooseStartPose(Room(6, 4), robot, navigation);
  EXPECT_LT((empty.xy_m - Eigen::Vector2d(3.0, 2.0)).norm(), navigation.cell_size_m);

  // With the cabinet: as far from obstacles (clearance counts up to 1 m), nearest the furniture's
  // centre among those, and facing it.
  const platform::BasePose start = ChooseStartPose(CabinetRoom(), robot, navigation);
  const Eigen::Vector2d cabinet(5.0, 0.75);
  const double clearance_m = 1.0 + robot.base_radius_m;
  EXPECT_GE(start.xy_m.x(), clearance_m - navigation.cell_size_m);
  EXPECT_GE(start.xy_m.y(), clearance_m - navigation.cell_size_m);
  EXPECT_LE(start.xy_m.y(), 4.0 - clearance_m + navigation.cell_size_m);
  const Eigen::Vector2d nearest_on_cabinet(std::clamp(start.xy_m.x(), 4.5, 5.5), std::clamp(start.xy_m.y(), 0.5, 1.0));
  EXPECT_GE((start.xy_m - nearest_on_cabinet).norm(), clearance_m - navigation.cell_size_m);
  const Eigen::Vector2d to_cabinet = cabinet - start.xy_m;
  EXPECT_NEAR(start.theta_rad, std::atan2(to_cabinet.y(), to_cabinet.x()), 1e-9);

  // The operator's choice is where the simulated robot stands.
  const world::Scene scene = CabinetRoom();
  const SimulatedRobot placed(scene, SmallSensor(), robot, navigation, 1);
  EXPECT_EQ(placed.base().xy_m, start.xy_m);
  EXPECT_EQ(placed.base().theta_rad, start.theta_rad);
}

TEST(StartPoseTest, NoFreeFloorIsAnInputError) {
  // A room narrower than the robot.
  EXPECT_THROW(ChooseStartPose(Room(0.3, 0.3), platform::RobotOptions(), navigation::NavigatorOptions()),
               InputError);
}

}  // namespace
}  // namespace objscan::sim
