#include "robot_protocol.h"

#include <gtest/gtest.h>

#include <cmath>

#include "objscan/common/error.h"

namespace objscan::ros_bridge {
namespace {

// A pose whose numbers need all 17 digits.
geometry::Pose3 OddPose() {
  return geometry::CameraPoseFromYawPitch(Eigen::Vector3d(1.0 / 3.0, -2.0 / 7.0, 1.1), 0.1 + 1e-13, -0.7);
}

TEST(RobotProtocolTest, MovesTravelBitForBit) {
  RobotRequest request;
  request.id = 42;
  request.kind = RequestKind::kMoveCamera;
  request.T_world_camera = OddPose();
  request.map_revision = 7;
  const RobotRequest back = DecodeRequest(EncodeRequest(request));
  EXPECT_EQ(back.id, 42u);
  EXPECT_EQ(back.kind, RequestKind::kMoveCamera);
  EXPECT_EQ(back.map_revision, 7u);
  EXPECT_EQ(back.T_world_camera.matrix(), request.T_world_camera.matrix()) << "not exact: runs would drift apart";
}

TEST(RobotProtocolTest, CapturesSayWhenTheyWereAsked) {
  RobotRequest request;
  request.id = 5;
  request.kind = RequestKind::kCapture;
  request.asked_stamp_ns = 1764409825123456789ull;  // beyond a double's 53 bits: must stay exact
  const RobotRequest back = DecodeRequest(EncodeRequest(request));
  EXPECT_EQ(back.kind, RequestKind::kCapture);
  EXPECT_EQ(back.asked_stamp_ns, request.asked_stamp_ns);
  // A capture that does not say (an older bag) reads as 0, and writes as it was.
  request.asked_stamp_ns = 0;
  const std::string unsaid = EncodeRequest(request);
  EXPECT_EQ(unsaid.find("asked_stamp_ns"), std::string::npos) << unsaid;
  EXPECT_EQ(DecodeRequest(unsaid).asked_stamp_ns, 0u);
}

TEST(RobotProtocolTest, MapsTravelWithTheBody) {
  RobotRequest request;
  request.id = 3;
  request.kind = RequestKind::kMap;
  request.map.revision = 2;
  request.map.grid.cell_size_m = 0.05;
  request.map.grid.origin_m = Eigen::Vector2d(-1.0 / 3.0, 0.1);
  request.map.grid.width = 3;
  request.map.grid.height = 2;
  using navigation::CellState;
  request.map.grid.cells = {CellState::kFree,     CellState::kOccupied, CellState::kUnknown,
                            CellState::kUnknown,  CellState::kFree,     CellState::kOccupied};
  request.map.robot_radius_m = 0.3;
  request.map.robot_height_m = 1.5;
  request.map.options.smooth_path = false;
  request.map.options.start_escape_m = 0.25;
  const RobotRequest back = DecodeRequest(EncodeRequest(request));
  EXPECT_EQ(back.map.revision, 2u);
  EXPECT_EQ(back.map.grid.origin_m, request.map.grid.origin_m);
  EXPECT_EQ(back.map.grid.width, 3);
  EXPECT_EQ(back.map.grid.height, 2);
  EXPECT_EQ(back.map.grid.cells, request.map.grid.cells);
  EXPECT_EQ(back.map.robot_radius_m, 0.3);
  EXPECT_EQ(back.map.robot_height_m, 1.5);
  EXPECT_FALSE(back.map.options.smooth_path);
  EXPECT_EQ(back.map.options.start_escape_m, 0.25);
}

TEST(RobotProtocolTest, ResponsesCarryStatusPathAndState) {
  RobotResponse r;
  r.id = 9;
  r.status = platform::ReachStatus::kOk;
  r.path.status = navigation::PlanStatus::kReached;
  r.path.waypoints = {Eigen::Vector2d(0.1, 0.2), Eigen::Vector2d(1.0 / 3.0, 2.0)};
  r.path.length_m = 1.9;
  r.path.grid_length_m = 2.05;
  r.path.expansions = 120;
  r.T_world_camera_taken = OddPose();
  r.state.base.xy_m = Eigen::Vector2d(1.0 / 3.0, 2.0);
  r.state.base.theta_rad = M_PI / 7.0;
  r.state.T_world_camera = OddPose();
  r.state.travel.distance_m = 4.25;
  r.state.travel.time_s = 1.0 / 9.0;
  r.state.travel.turn_rad = 0.5;
  r.state.travel.moves = 3;
  r.state.travel.arm_moves = 2;
  r.world_name = "bathroom";
  r.intrinsics.fx_px = 131.25;
  const RobotResponse back = DecodeResponse(EncodeResponse(r));
  EXPECT_EQ(back.id, 9u);
  EXPECT_EQ(back.status, platform::ReachStatus::kOk);
  EXPECT_EQ(back.path.status, navigation::PlanStatus::kReached);
  EXPECT_EQ(back.path.waypoints, r.path.waypoints);
  EXPECT_EQ(back.path.length_m, 1.9);
  EXPECT_EQ(back.path.grid_length_m, 2.05);
  EXPECT_EQ(back.path.expansions, 120);
  EXPECT_EQ(back.T_world_camera_taken.matrix(), r.T_world_camera_taken.matrix());
  EXPECT_EQ(back.state.base.xy_m, r.state.base.xy_m);
  EXPECT_EQ(back.state.base.theta_rad, r.state.base.theta_rad);
  EXPECT_EQ(back.state.travel.time_s, r.state.travel.time_s);
  EXPECT_EQ(back.state.travel.arm_moves, 2);
  EXPECT_EQ(back.world_name, "bathroom");
  EXPECT_EQ(back.intrinsics.fx_px, 131.25);
  EXPECT_TRUE(back.error.empty());

  for (platform::ReachStatus s : {platform::ReachStatus::kNoFreeBase, platform::ReachStatus::kUnreachable,
                                  platform::ReachStatus::kPitchOutOfRange}) {
    r.status = s;
    EXPECT_EQ(DecodeResponse(EncodeResponse(r)).status, s) << platform::ReachStatusName(s);
  }
  r.error = "map revision 3 unknown";
  EXPECT_EQ(DecodeResponse(EncodeResponse(r)).error, r.error);
}

TEST(RobotProtocolTest, OtherTextIsOneClearError) {
  for (const std::string& text : {std::string("not json"), std::string("[1, 2]"), std::string("{\"id\": 1}"),
                                 std::string("{\"id\": 1, \"kind\": \"fly\"}"),
                                 std::string("{\"id\": \"one\", \"kind\": \"hello\"}")}) {
    try {
      DecodeRequest(text);
      FAIL() << text;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("robot protocol: ", 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  EXPECT_THROW(DecodeResponse("{\"id\": 1}"), InputError);
}

}  // namespace
}  // namespace objscan::ros_bridge
