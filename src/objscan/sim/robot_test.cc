#include "objscan/sim/robot.h"

#include <gtest/gtest.h>

#include <cmath>

#include "objscan/common/error.h"
#include "objscan/sim/ground_truth_occupancy.h"
#include "objscan/sim/test_scenes.h"
#include "objscan/world/procedural/procedural.h"

namespace objscan::sim {
namespace {

using testing::BoxObject;
using testing::Room;
using navigation::Navigator;
using platform::BasePose;
using platform::ReachStatus;
using platform::ReachStatusName;
using platform::RobotOptions;
using navigation::NavigatorOptions;

void ExpectSamePose(const geometry::Pose3& a, const geometry::Pose3& b, double tol = 1e-9) {
  EXPECT_LT((a.translation() - b.translation()).norm(), tol);
  EXPECT_LT((a.linear() - b.linear()).norm(), tol);
}

TEST(RobotTest, CameraPoseFromBaseAndArm) {
  BasePose base;
  base.xy_m = Eigen::Vector2d(1, 2);
  base.theta_rad = M_PI / 2;
  ArmSetting arm;
  arm.camera_offset_base_m = Eigen::Vector2d(0.3, 0.0);  // 0.3 m ahead of the base
  arm.camera_height_m = 1.2;
  arm.yaw_rel_rad = -M_PI / 2;                           // looking along world +X
  arm.pitch_rad = geometry::DegToRad(-30);
  ExpectSamePose(Robot::CameraPoseOf(base, arm),
                 geometry::CameraPoseFromYawPitch(Eigen::Vector3d(1, 2.3, 1.2), 0.0, geometry::DegToRad(-30)));
}

TEST(RobotTest, ReachesACameraPoseAcrossAnOpenRoomAndAccountsTravel) {
  const world::Scene scene = Room(6, 4);
  const GroundTruthOccupancy source(scene);
  const RobotOptions options;
  const Navigator nav(source, options.base_radius_m, options.height_m);
  BasePose start;
  start.xy_m = Eigen::Vector2d(1.0, 2.0);
  Robot robot(options, start);
  const geometry::Pose3 wanted =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(4.0, 2.0, 1.2), 0.0, geometry::DegToRad(-20));
  const ReachPlan plan = robot.MoveTo(wanted, nav);
  ASSERT_EQ(plan.status, ReachStatus::kOk) << ReachStatusName(plan.status);
  ExpectSamePose(plan.T_world_camera, wanted);
  ExpectSamePose(robot.CameraPose(), wanted);
  // Nearest reaching base: 0.6 m behind the camera, straight ahead of the start.
  EXPECT_NEAR(robot.base().xy_m.x(), 3.4, 1e-9);
  EXPECT_NEAR(robot.base().xy_m.y(), 2.0, 1e-9);
  EXPECT_LE(robot.arm().camera_offset_base_m.norm(), options.max_reach_m + 1e-9);
  EXPECT_NEAR(plan.path.length_m, 2.4, 1e-9);
  // 2.4 m at 0.3 m/s, no turning, one arm move of 2 s.
  EXPECT_NEAR(plan.time_s, 2.4 / 0.3 + 2.0, 1e-9);
  EXPECT_NEAR(robot.travel().distance_m, 2.4, 1e-9);
  EXPECT_NEAR(robot.travel().time_s, 10.0, 1e-9);
  EXPECT_EQ(robot.travel().arm_moves, 1);

  // Turn around: the camera now looks back at the start, 1 m to the left of it.
  const geometry::Pose3 back =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(2.0, 3.0, 0.8), M_PI, geometry::DegToRad(10));
  const ReachPlan second = robot.MoveTo(back, nav);
  ASSERT_TRUE(second.ok());
  ExpectSamePose(robot.CameraPose(), back);
  double turn = 0;
  const double expected = robot.TravelTime(second.path, 0.0, true, nullptr, &turn);
  EXPECT_GT(turn, M_PI / 2);  // had to turn at least a quarter
  EXPECT_NEAR(second.time_s, expected, 1e-9);
  EXPECT_NEAR(second.time_s, second.path.length_m / 0.3 + geometry::RadToDeg(turn) / 30.0 + 2.0, 1e-9);
  EXPECT_NEAR(robot.travel().time_s, 10.0 + second.time_s, 1e-9);
  EXPECT_NEAR(robot.travel().distance_m, 2.4 + second.path.length_m, 1e-9);
  EXPECT_EQ(robot.travel().moves, 2);

  // Within reach already: only the arm moves.
  const geometry::Pose3 near = geometry::CameraPoseFromYawPitch(
      Eigen::Vector3d(robot.base().xy_m.x() + 0.2, robot.base().xy_m.y(), 1.5), 1.0, 0.0);
  const ReachPlan arm_only = robot.MoveTo(near, nav);
  ASSERT_TRUE(arm_only.ok());
  EXPECT_DOUBLE_EQ(arm_only.path.length_m, 0.0);
  EXPECT_DOUBLE_EQ(arm_only.time_s, options.arm_move_s);
}

TEST(RobotTest, ArmLimitsAreStatuses) {
  const world::Scene scene = Room(4, 4);
  const GroundTruthOccupancy source(scene);
  const RobotOptions options;
  const Navigator nav(source, options.base_radius_m, options.height_m);
  BasePose start;
  start.xy_m = Eigen::Vector2d(1, 1);
  Robot robot(options, start);
  auto pose = [](double z, double pitch_deg) {
    return geometry::CameraPoseFromYawPitch(Eigen::Vector3d(2, 2, z), 0.3, geometry::DegToRad(pitch_deg));
  };
  EXPECT_EQ(robot.PlanTo(pose(0.2, 0), nav).status, ReachStatus::kCameraHeightOutOfRange);
  EXPECT_EQ(robot.PlanTo(pose(1.9, 0), nav).status, ReachStatus::kCameraHeightOutOfRange);
  EXPECT_EQ(robot.PlanTo(pose(1.0, -75), nav).status, ReachStatus::kPitchOutOfRange);
  EXPECT_EQ(robot.PlanTo(pose(1.0, 35), nav).status, ReachStatus::kPitchOutOfRange);
  EXPECT_TRUE(robot.PlanTo(pose(0.3, -70), nav).ok());
  EXPECT_TRUE(robot.PlanTo(pose(1.8, 30), nav).ok());
  // A failed move changes nothing.
  const ReachPlan failed = robot.MoveTo(pose(0.1, 0), nav);
  EXPECT_FALSE(failed.ok());
  EXPECT_EQ(robot.travel().moves, 0);
  EXPECT_DOUBLE_EQ(robot.travel().time_s, 0.0);
}

TEST(RobotTest, NoFreeBaseAndUnreachableAreStatuses) {
  world::Scene scene = Room(8, 5);
  scene.Add(BoxObject({1.0, 1.0, 0}, {3.0, 3.0, 0.75}));  // a big table
  // A closed pen.
  scene.Add(BoxObject({5.0, 1.0, 0}, {7.5, 1.1, 1.0}));
  scene.Add(BoxObject({5.0, 3.4, 0}, {7.5, 3.5, 1.0}));
  scene.Add(BoxObject({5.0, 1.0, 0}, {5.1, 3.5, 1.0}));
  scene.Add(BoxObject({7.4, 1.0, 0}, {7.5, 3.5, 1.0}));
  const GroundTruthOccupancy source(scene);
  const RobotOptions options;
  const Navigator nav(source, options.base_radius_m, options.height_m);
  BasePose start;
  start.xy_m = Eigen::Vector2d(4.0, 4.3);
  Robot robot(options, start);
  // Above the middle of the table: all floor within 0.6 m is under the table.
  const geometry::Pose3 over_table =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(2.0, 2.0, 1.5), 0.0, geometry::DegToRad(-60));
  EXPECT_EQ(robot.PlanTo(over_table, nav).status, ReachStatus::kNoFreeBase);
  // Near the table's edge it is fine.
  const geometry::Pose3 table_edge =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(2.0, 3.1, 1.5), -M_PI / 2, geometry::DegToRad(-60));
  EXPECT_TRUE(robot.PlanTo(table_edge, nav).ok());
  // Inside the pen.
  const geometry::Pose3 in_pen = geometry::CameraPoseFromYawPitch(Eigen::Vector3d(6.25, 2.25, 1.0), 0.0, 0.0);
  EXPECT_EQ(robot.PlanTo(in_pen, nav).status, ReachStatus::kUnreachable);
  // Starting inside an obstacle.
  BasePose stuck;
  stuck.xy_m = Eigen::Vector2d(2.0, 2.0);
  const Robot stuck_robot(options, stuck);
  EXPECT_EQ(stuck_robot.PlanTo(table_edge, nav).status, ReachStatus::kStartBlocked);
}

TEST(RobotTest, ReachesViewsInAProceduralBedroom) {
  const world::Scene scene = world::procedural::GenerateRoom("bedroom", 1);
  const GroundTruthOccupancy source(scene);
  const RobotOptions options;
  const Navigator nav(source, options.base_radius_m, options.height_m);
  const geometry::Aabb3 room = scene.Bounds();
  Eigen::Vector2d start_xy;
  ASSERT_TRUE(nav.NearestFree(room.Center().head<2>(), 3.0, &start_xy));
  BasePose start;
  start.xy_m = start_xy;
  Robot robot(options, start);
  int reached = 0;
  for (const auto& object : scene.objects()) {
    if (object.IsStructural()) continue;
    // Look at the object from 1.2 m away on the room-centre side, at 1.3 m height.
    const Eigen::Vector3d target = scene.ObjectBounds(object).Center();
    Eigen::Vector3d from = target;
    const Eigen::Vector2d away = (start_xy - target.head<2>()).normalized();
    from.head<2>() += 1.2 * away;
    from.z() = 1.3;
    geometry::Pose3 wanted;
    ASSERT_TRUE(geometry::CameraPoseLookAt(from, target, &wanted));
    const ReachPlan plan = robot.MoveTo(wanted, nav);
    if (plan.status == ReachStatus::kPitchOutOfRange) continue;
    if (!plan.ok()) continue;
    ++reached;
    ExpectSamePose(robot.CameraPose(), wanted, 1e-6);
    EXPECT_TRUE(nav.IsFree(robot.base().xy_m));
    EXPECT_LE((robot.base().xy_m - from.head<2>()).norm(), options.max_reach_m + 1e-9);
  }
  EXPECT_GT(reached, 0);
  EXPECT_GT(robot.travel().distance_m, 0.0);
  EXPECT_GE(robot.travel().time_s, robot.travel().distance_m / options.speed_m_per_s);
}

// A robot whose own cell became blocked (an obstacle seen late, closer than its radius) backs out to
// the nearest free cell: its path search starts there, not from the blocked cell, which reaches nothing.
TEST(RobotTest, ABlockedStartWithinTheEscapeRadiusStillReachesFarViews) {
  world::Scene scene = Room(6, 4);
  scene.Add(BoxObject({2.0, 2.0, 0}, {2.5, 2.5, 0.8}));
  const GroundTruthOccupancy source(scene);
  const RobotOptions options;
  NavigatorOptions nav_options;
  const Navigator nav(source, options.base_radius_m, options.height_m, nav_options);
  BasePose start;
  start.xy_m = Eigen::Vector2d(1.85, 2.25);  // 0.15 m from the box: inside its inflation
  ASSERT_FALSE(nav.IsFree(start.xy_m));
  Robot robot(options, start);
  const geometry::Pose3 far =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(5.0, 1.0, 1.2), 0.0, geometry::DegToRad(-20));
  const ReachPlan plan = robot.PlanTo(far, nav);
  ASSERT_EQ(plan.status, ReachStatus::kOk) << ReachStatusName(plan.status);
  // The path leaves from the robot's own position.
  EXPECT_LT((plan.path.waypoints.front() - start.xy_m).norm(), 1e-9);
  // Without the straight move, the route through the inflated cells leaves too, and its length counts.
  nav_options.start_escape_m = 0.0;
  const Navigator routed(source, options.base_radius_m, options.height_m, nav_options);
  const ReachPlan via_route = robot.PlanTo(far, routed);
  ASSERT_EQ(via_route.status, ReachStatus::kOk) << ReachStatusName(via_route.status);
  EXPECT_LT((via_route.path.waypoints.front() - start.xy_m).norm(), 1e-9);
  // Without either escape the start stays blocked.
  nav_options.start_escape_route_m = 0.0;
  const Navigator strict(source, options.base_radius_m, options.height_m, nav_options);
  EXPECT_EQ(robot.PlanTo(far, strict).status, ReachStatus::kStartBlocked);
}

}  // namespace
}  // namespace objscan::sim
