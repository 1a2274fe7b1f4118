#pragma once
// platform::Platform over a link to a robot in another process (robot_protocol.h): the ROS node's
// platform, with the transport behind RobotLink (ros/objscan_ros_node.cc: roscpp topics; tests: a
// RobotServer in the same process). A link that fails (no answer, no frame in time) ends the scan
// without losing it: the platform remembers the one-line reason, captures nothing more and reaches
// nowhere, so the scanner stops and its run is written as far as it got.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "objscan/platform/platform.h"
#include "objscan/platform/robot_options.h"
#include "robot_protocol.h"

namespace objscan::ros_bridge {

// The link lost the robot (one line: what did not come within how long).
class LinkError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class RobotLink {
 public:
  virtual ~RobotLink() = default;
  // Sends a request and returns the robot's response to it; throws LinkError when none comes.
  virtual RobotResponse Call(const RobotRequest& request) = 0;
  // Asks for a frame (a kCapture request) and returns the first depth frame taken after the call,
  // posed in the world; throws LinkError when none comes.
  virtual platform::DepthFrame Capture(std::uint64_t request_id) = 0;
};

class RemotePlatform : public platform::Platform {
 public:
  // Greets the robot (kHello: its world and intrinsics). `body`: the robot's footprint the
  // scanner's navigator inflates by (config section `robot`), sent with each map. `link` must
  // outlive the platform. Throws LinkError when the robot does not answer.
  RemotePlatform(RobotLink* link, const platform::RobotOptions& body);

  std::string world_name() const override { return world_name_; }
  platform::CameraIntrinsics intrinsics() const override { return intrinsics_; }
  platform::BasePose base() const override { return state_.base; }
  geometry::Pose3 T_world_camera() const override { return state_.T_world_camera; }
  platform::TravelStats travel() const override { return state_.travel; }
  platform::DepthFrame Capture() override;
  platform::ReachStatus CheckReach(const geometry::Pose3& T_world_camera,
                                   const navigation::Navigator& map) const override;
  platform::Move MoveCamera(const geometry::Pose3& T_world_camera, const navigation::Navigator& map) override;
  geometry::Pose3 TurnCamera(const geometry::Pose3& T_world_camera) override;

  // Why the link failed (empty while it works); the scan after it saw and moved no more.
  const std::string& failure() const { return failure_; }
  // Maps sent so far (each a new revision).
  std::uint64_t maps_sent() const { return map_revision_; }

 private:
  // A call; on a failed link (now or before) nullopt, with failure_ set.
  std::optional<RobotResponse> Call(RobotRequest request) const;
  // Sends `map` when it differs from the last one sent; false when the link failed.
  bool SendMap(const navigation::Navigator& map) const;

  RobotLink* link_;
  platform::RobotOptions body_;
  std::string world_name_;
  platform::CameraIntrinsics intrinsics_;
  // The queries are const for the scanner but talk to the robot: the link's bookkeeping is mutable.
  mutable RobotState state_;
  mutable std::uint64_t next_id_ = 1;
  mutable std::uint64_t map_revision_ = 0;
  mutable navigation::OccupancyGrid2D sent_grid_;
  mutable navigation::NavigatorOptions sent_options_;
  mutable std::string failure_;
};

}  // namespace objscan::ros_bridge
