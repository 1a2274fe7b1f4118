#pragma once
// How objscan's scanner asks a robot for what platform::Platform offers, as messages: one request,
// one response with the same id. The ROS 1 nodes carry them as JSON text (std_msgs/String) on
// objscan/robot_request and objscan/robot_response; a ROS 2 bridge can carry the same text. Numbers
// are written so that they read back exactly (a run over ROS takes the same decisions as one in a
// single process).
//
// The scanner plans on its own map (platform.h), so the map travels too: a kMap request carries the
// navigation grid and the body it is inflated for, and every check or move names the map revision
// it drives on.
#include <cstdint>
#include <string>

#include "objscan/geometry/pose.h"
#include "objscan/navigation/navigator.h"
#include "objscan/platform/platform.h"

namespace objscan::ros_bridge {

enum class RequestKind {
  kHello,       // who are you: world name, intrinsics, where the robot is
  kMap,         // the navigation map later requests name by revision
  kCheckReach,  // Platform::CheckReach (nothing moves)
  kMoveCamera,  // Platform::MoveCamera
  kTurnCamera,  // Platform::TurnCamera
  kCapture,     // take one depth frame now (a simulator renders on request; a real camera streams
                // and ignores it); the frame comes on the image topics, the response says it was sent
};
const char* RequestKindName(RequestKind kind);

// The grid the base drives on and what the robot needs to build the same navigator from it.
struct NavigationMap {
  std::uint64_t revision = 0;
  navigation::OccupancyGrid2D grid;
  double robot_radius_m = 0.25;
  double robot_height_m = 1.8;
  navigation::NavigatorOptions options;
};

struct RobotRequest {
  std::uint64_t id = 0;
  RequestKind kind = RequestKind::kHello;
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();  // kCheckReach, kMoveCamera, kTurnCamera
  std::uint64_t map_revision = 0;                                // kCheckReach, kMoveCamera
  NavigationMap map;                                             // kMap
  // kCapture: when objscan asked (ROS time, ns; 0 = not said). The frame is the first depth image
  // stamped at or after it, live and when a bag is played back: a recorder may write the image
  // before the request, so the order in a bag does not say which request an image answers.
  std::uint64_t asked_stamp_ns = 0;
};

// Where the robot is after a request, sent with every response.
struct RobotState {
  platform::BasePose base;
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();
  platform::TravelStats travel;
};

struct RobotResponse {
  std::uint64_t id = 0;
  // Not empty: the robot could not serve the request (one line: an unknown map revision, a pose
  // that is not finite); status and path are then meaningless.
  std::string error;
  platform::ReachStatus status = platform::ReachStatus::kOk;  // kCheckReach, kMoveCamera
  navigation::Path2D path;                                   // kMoveCamera (when ok)
  geometry::Pose3 T_world_camera_taken = geometry::Pose3::Identity();  // kMoveCamera, kTurnCamera
  RobotState state;
  std::string world_name;                  // kHello
  platform::CameraIntrinsics intrinsics;   // kHello
};

// JSON text of a message and back. Decoding throws InputError ("robot protocol: ...") on text that
// is not a message of this protocol.
std::string EncodeRequest(const RobotRequest& request);
RobotRequest DecodeRequest(const std::string& text);
std::string EncodeResponse(const RobotResponse& response);
RobotResponse DecodeResponse(const std::string& text);

}  // namespace objscan::ros_bridge
