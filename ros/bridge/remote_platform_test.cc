#include "remote_platform.h"

#include <gtest/gtest.h>

#include "loopback_link.h"
#include "objscan/platform/testing/platform_contract.h"
#include "objscan/sim/ground_truth_occupancy.h"
#include "objscan/sim/simulated_robot.h"
#include "objscan/sim/test_scenes.h"

namespace objscan::ros_bridge {
namespace {

using sim::testing::CabinetRoom;
using sim::testing::SmallSensor;

platform::BasePose Start() {
  platform::BasePose start;
  start.xy_m = Eigen::Vector2d(1.0, 2.0);
  return start;
}

struct Fixture {
  world::Scene scene = CabinetRoom();
  platform::RobotOptions body;
  sim::GroundTruthOccupancy truth{scene};
  navigation::Navigator map{truth, body.base_radius_m, body.height_m};
  geometry::Pose3 reachable =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(3.5, 2.5, 1.2), -0.5, geometry::DegToRad(-20));
  geometry::Pose3 too_high =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(3.5, 2.5, body.max_camera_height_m + 0.5), 0.0, 0.0);
};

TEST(RemotePlatformTest, KeepsThePlatformContractOverTheProtocol) {
  Fixture f;
  sim::SimulatedRobot robot(f.scene, SmallSensor(), f.body, Start(), /*seed=*/3);
  RobotServer server(&robot);
  LoopbackLink link(&server);
  RemotePlatform remote(&link, f.body);
  EXPECT_EQ(remote.world_name(), "room");
  platform::testing::ExpectPlatformContract(&remote, f.map, f.reachable, f.too_high);
  EXPECT_TRUE(remote.failure().empty()) << remote.failure();
  EXPECT_EQ(remote.maps_sent(), 1u) << "the same map is sent once";
}

// The robot served over the protocol answers, moves and sees as the robot itself.
TEST(RemotePlatformTest, SameAnswersAndFramesAsTheRobotItself) {
  Fixture f;
  sim::SimulatedRobot local(f.scene, SmallSensor(), f.body, Start(), /*seed=*/5);
  sim::SimulatedRobot served(f.scene, SmallSensor(), f.body, Start(), /*seed=*/5);
  RobotServer server(&served);
  LoopbackLink link(&server);
  RemotePlatform remote(&link, f.body);
  const platform::Move a = local.MoveCamera(f.reachable, f.map);
  const platform::Move b = remote.MoveCamera(f.reachable, f.map);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a.path.waypoints, b.path.waypoints);
  EXPECT_EQ(a.T_world_camera.matrix(), b.T_world_camera.matrix());
  EXPECT_EQ(local.travel().time_s, remote.travel().time_s);
  const platform::DepthFrame fa = local.Capture();
  const platform::DepthFrame fb = remote.Capture();
  EXPECT_EQ(fa.depth_m, fb.depth_m) << "the noise is drawn once per capture on either side";
  EXPECT_EQ(fa.gt_instance, fb.gt_instance);
  EXPECT_EQ(fa.T_world_camera.matrix(), fb.T_world_camera.matrix());
}

// A link that answers the greeting and then falls silent.
class DyingLink : public RobotLink {
 public:
  explicit DyingLink(RobotServer* server) : inner_(server) {}
  RobotResponse Call(const RobotRequest& request) override {
    if (calls_++ > 0) throw LinkError("no response on /objscan/robot_response within 10 s");
    return inner_.Call(request);
  }
  platform::DepthFrame Capture(std::uint64_t) override { throw LinkError("no depth frame within 10 s"); }

 private:
  LoopbackLink inner_;
  int calls_ = 0;
};

TEST(RemotePlatformTest, ALostLinkStopsTheRobotAndSaysWhy) {
  Fixture f;
  sim::SimulatedRobot robot(f.scene, SmallSensor(), f.body, Start(), /*seed=*/3);
  RobotServer server(&robot);
  DyingLink link(&server);
  RemotePlatform remote(&link, f.body);
  const platform::BasePose start = remote.base();
  EXPECT_EQ(remote.CheckReach(f.reachable, f.map), platform::ReachStatus::kUnreachable);
  EXPECT_EQ(remote.failure(), "no response on /objscan/robot_response within 10 s");
  EXPECT_FALSE(remote.MoveCamera(f.reachable, f.map).ok());
  EXPECT_EQ(remote.base().xy_m, start.xy_m);
  const platform::DepthFrame frame = remote.Capture();
  EXPECT_EQ(frame.depth_m.size(), static_cast<std::size_t>(remote.intrinsics().NumPixels()));
  EXPECT_EQ(frame.NumValid(), 0u) << "nothing seen after the link failed";
  EXPECT_EQ(remote.failure(), "no response on /objscan/robot_response within 10 s") << "the first reason stays";
}

TEST(RemotePlatformTest, AServerWithoutTheNamedMapSaysSo) {
  Fixture f;
  sim::SimulatedRobot robot(f.scene, SmallSensor(), f.body, Start(), /*seed=*/3);
  RobotServer server(&robot);
  RobotRequest check;
  check.id = 5;
  check.kind = RequestKind::kCheckReach;
  check.T_world_camera = f.reachable;
  check.map_revision = 4;
  const RobotResponse r = server.Serve(check);
  EXPECT_EQ(r.id, 5u);
  EXPECT_NE(r.error.find("map revision 4"), std::string::npos) << r.error;
}

}  // namespace
}  // namespace objscan::ros_bridge
