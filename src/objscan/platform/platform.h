#pragma once
// The robot seam: what the method needs of a robot carrying a depth camera, and no more. The scanner
// (scanning/scanner.h) drives any implementation: objscan's simulator (sim/simulated_robot.h) or a
// real robot. The method plans where the base may drive on its own map (navigation::Navigator over
// what the robot has seen) and passes it in; a platform answers for its body: where it is, whether
// and how its camera reaches a pose, and the frames it takes from there.
#include <Eigen/Core>
#include <string>

#include "objscan/geometry/pose.h"
#include "objscan/navigation/navigator.h"
#include "objscan/platform/depth_frame.h"

namespace objscan::platform {

// The base on the floor.
struct BasePose {
  Eigen::Vector2d xy_m = Eigen::Vector2d::Zero();
  double theta_rad = 0.0;  // heading about world Z, 0 = +X
};

enum class ReachStatus {
  kOk,
  kCameraHeightOutOfRange,  // the wanted camera is too low or too high for the robot
  kPitchOutOfRange,         // the wanted camera looks too far down or up
  kNoFreeBase,              // no free floor within reach of the wanted camera position
  kStartBlocked,            // the robot's current base position is not free on the map
  kUnreachable,             // free base positions exist but no path leads there
};
const char* ReachStatusName(ReachStatus status);

// What a move of the camera did.
struct Move {
  ReachStatus status = ReachStatus::kUnreachable;
  navigation::Path2D path;  // the base's path from where it stood (when ok)
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();  // the camera pose taken (when ok)
  bool ok() const { return status == ReachStatus::kOk; }
};

// What the robot has travelled since it was put down.
struct TravelStats {
  double distance_m = 0.0;
  double time_s = 0.0;  // driving, turning and camera moves (navigate_sim in the simulator)
  double turn_rad = 0.0;
  int moves = 0;        // moves made
  int arm_moves = 0;    // moves that changed the camera's setting on the base
};

class Platform {
 public:
  virtual ~Platform() = default;

  // The name of the world the robot is in (the simulated scene's, a site's), for the run record.
  virtual std::string world_name() const = 0;
  // The depth camera's intrinsics (every frame carries them too).
  virtual CameraIntrinsics intrinsics() const = 0;

  // Where the robot is now; before the first move, where it was put down (the scan's start).
  virtual BasePose base() const = 0;
  virtual geometry::Pose3 T_world_camera() const = 0;
  virtual TravelStats travel() const = 0;

  // A depth frame from where the camera is now (frame.T_world_camera: the pose at capture).
  virtual DepthFrame Capture() = 0;

  // Whether the camera can take T_world_camera, the base driving on `map` (a query: nothing moves).
  virtual ReachStatus CheckReach(const geometry::Pose3& T_world_camera, const navigation::Navigator& map) const = 0;
  // Drives the base on `map` and sets the camera to T_world_camera; nothing moves unless the move is ok.
  virtual Move MoveCamera(const geometry::Pose3& T_world_camera, const navigation::Navigator& map) = 0;
  // Turns the camera above the base where it stands, to the height, yaw and pitch of T_world_camera
  // (no driving, so it needs no map: the first look around). Returns the camera pose taken.
  virtual geometry::Pose3 TurnCamera(const geometry::Pose3& T_world_camera) = 0;
};

}  // namespace objscan::platform
