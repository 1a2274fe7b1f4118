#pragma once
// What every platform::Platform must do, as gtest checks shared by its implementations (the
// simulator's, sim/simulated_robot_test.cc; a test's own, tests/without_sim/): the scanner relies on
// exactly this. Test-only, header-only.
#include <gtest/gtest.h>

#include <cmath>

#include "objscan/geometry/pose.h"
#include "objscan/navigation/navigator.h"
#include "objscan/platform/platform.h"

namespace objscan::platform::testing {

// Within `tol` (0: exactly the same pose).
inline void ExpectSamePose(const geometry::Pose3& a, const geometry::Pose3& b, double tol) {
  EXPECT_LE((a.translation() - b.translation()).norm(), tol) << a.translation().transpose() << " vs "
                                                             << b.translation().transpose();
  EXPECT_LE((a.linear() - b.linear()).norm(), tol);
}

inline void ExpectSameBase(const BasePose& a, const BasePose& b) {
  EXPECT_EQ(a.xy_m, b.xy_m);
  EXPECT_EQ(a.theta_rad, b.theta_rad);
}

// A frame is taken where the camera is, with the platform's intrinsics, and holds only depths in range.
inline void ExpectCaptureHere(Platform* platform) {
  const geometry::Pose3 here = platform->T_world_camera();
  const CameraIntrinsics k = platform->intrinsics();
  const DepthFrame frame = platform->Capture();
  ExpectSamePose(frame.T_world_camera, here, 0.0);
  EXPECT_EQ(frame.intrinsics.width_px, k.width_px);
  EXPECT_EQ(frame.intrinsics.height_px, k.height_px);
  EXPECT_EQ(frame.intrinsics.fx_px, k.fx_px);
  EXPECT_EQ(frame.intrinsics.fy_px, k.fy_px);
  EXPECT_EQ(frame.intrinsics.cx_px, k.cx_px);
  EXPECT_EQ(frame.intrinsics.cy_px, k.cy_px);
  ASSERT_EQ(frame.depth_m.size(), static_cast<std::size_t>(k.NumPixels()));
  std::size_t out_of_range = 0;
  for (float d : frame.depth_m) out_of_range += d != 0.f && (d < k.min_range_m || d > k.max_range_m);
  EXPECT_EQ(out_of_range, 0u);
  EXPECT_GT(frame.NumValid(), 0u) << "the contract's checks need a platform that sees something";
}

// The contract. `reachable` must be a roll-free camera pose the platform can take, driving on `map`,
// from where it stands; `unreachable` one it cannot (its camera too high, say).
inline void ExpectPlatformContract(Platform* platform, const navigation::Navigator& map,
                                   const geometry::Pose3& reachable, const geometry::Pose3& unreachable) {
  ExpectCaptureHere(platform);

  // Queries move nothing.
  const BasePose start = platform->base();
  const geometry::Pose3 start_camera = platform->T_world_camera();
  const TravelStats start_travel = platform->travel();
  EXPECT_EQ(platform->CheckReach(reachable, map), ReachStatus::kOk);
  EXPECT_NE(platform->CheckReach(unreachable, map), ReachStatus::kOk);
  ExpectSameBase(platform->base(), start);
  ExpectSamePose(platform->T_world_camera(), start_camera, 0.0);
  EXPECT_EQ(platform->travel().moves, start_travel.moves);

  // A move that cannot be made leaves the robot where it was.
  const Move refused = platform->MoveCamera(unreachable, map);
  EXPECT_FALSE(refused.ok());
  EXPECT_EQ(refused.status, platform->CheckReach(unreachable, map));
  ExpectSameBase(platform->base(), start);
  ExpectSamePose(platform->T_world_camera(), start_camera, 0.0);
  EXPECT_EQ(platform->travel().distance_m, start_travel.distance_m);

  // A move that can: the camera takes the pose, the base drove the path it reports, travel accounts it.
  const Move move = platform->MoveCamera(reachable, map);
  ASSERT_TRUE(move.ok()) << ReachStatusName(move.status);
  ExpectSamePose(move.T_world_camera, platform->T_world_camera(), 0.0);
  ExpectSamePose(platform->T_world_camera(), reachable, 1e-6);
  ASSERT_FALSE(move.path.waypoints.empty());
  EXPECT_LT((move.path.waypoints.front() - start.xy_m).norm(), map.options().start_escape_m + 1e-9);
  EXPECT_LT((move.path.waypoints.back() - platform->base().xy_m).norm(), 1e-9);
  EXPECT_TRUE(map.IsFree(platform->base().xy_m));
  EXPECT_NEAR(platform->travel().distance_m - start_travel.distance_m, move.path.length_m, 1e-9);
  EXPECT_GT(platform->travel().time_s, start_travel.time_s);
  EXPECT_EQ(platform->travel().moves, start_travel.moves + 1);
  ExpectCaptureHere(platform);

  // Turning the camera: above the base where it stands, at the wanted height, yaw and pitch.
  const BasePose before_turn = platform->base();
  const double yaw = 2.0, pitch = geometry::DegToRad(-25.0), height_m = 1.1;
  const geometry::Pose3 wanted = geometry::CameraPoseFromYawPitch(
      Eigen::Vector3d(before_turn.xy_m.x(), before_turn.xy_m.y(), height_m), yaw, pitch);
  const geometry::Pose3 turned = platform->TurnCamera(wanted);
  ExpectSamePose(turned, platform->T_world_camera(), 0.0);
  ExpectSamePose(turned, wanted, 1e-9);
  EXPECT_EQ(platform->base().xy_m, before_turn.xy_m);
  EXPECT_EQ(platform->travel().distance_m - start_travel.distance_m, move.path.length_m);
  ExpectCaptureHere(platform);
}

}  // namespace objscan::platform::testing
