#pragma once
// A RobotLink that plays a recorded scan back from a rosbag: the conversation with the robot
// (objscan/robot_request, objscan/robot_response), the depth frames with their camera info (and
// ground-truth instances) and tf, as `rosbag record` keeps them (docs/ros.md). The scanner asks again
// what it asked when the bag was recorded (same scene, seed and config), and each request gets the
// recorded response and each capture the first depth frame stamped at or after it: the
// reconstruction and the whole run come back without a robot or a ROS master. A run that asks
// otherwise than the recorded one (another seed or config) stops at the first request that differs,
// with one line naming it.
#include <cstdint>
#include <memory>
#include <string>

#include "remote_platform.h"

namespace objscan::ros_bridge {

class BagLink : public RobotLink {
 public:
  // Reads `bag_path` (throws InputError naming the file when it cannot be read or holds no
  // conversation). `world_frame`: the tf frame of the camera poses; `ground_truth`: read the
  // instance images too.
  BagLink(const std::string& bag_path, const std::string& world_frame, bool ground_truth);
  ~BagLink() override;

  RobotResponse Call(const RobotRequest& request) override;
  platform::DepthFrame Capture(std::uint64_t request_id) override;

 private:
  struct Recording;
  std::unique_ptr<Recording> recording_;
  std::string bag_path_;
  std::string world_frame_;
  bool ground_truth_;
};

}  // namespace objscan::ros_bridge
