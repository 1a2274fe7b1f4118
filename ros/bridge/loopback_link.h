#pragma once
// A RobotLink to a RobotServer in the same process, through the same text and image encodings the
// ROS nodes send: the protocol and the conversions tested without a ROS master.
#include "depth_image.h"
#include "pose_conversion.h"
#include "remote_platform.h"
#include "robot_server.h"

namespace objscan::ros_bridge {

class LoopbackLink : public RobotLink {
 public:
  explicit LoopbackLink(RobotServer* server) : server_(server) {}

  RobotResponse Call(const RobotRequest& request) override {
    return DecodeResponse(EncodeResponse(server_->Serve(DecodeRequest(EncodeRequest(request)))));
  }

  // The frame as the nodes send it: a 32FC1 image, a camera info, the camera pose as a transform.
  platform::DepthFrame Capture(std::uint64_t) override {
    const platform::DepthFrame sent = server_->Capture();
    platform::DepthFrame frame;
    const ImageBuffer depth = DepthImageFromMetres(sent.depth_m, sent.width(), sent.height());
    frame.depth_m = DepthMetresFromImage(depth, "loopback depth");
    frame.intrinsics = IntrinsicsFromCameraInfo(CameraInfoFromIntrinsics(sent.intrinsics), sent.intrinsics.min_range_m,
                                                sent.intrinsics.max_range_m, "loopback camera info");
    frame.T_world_camera = PoseFromTransform(TransformFromPose(sent.T_world_camera), "loopback camera pose");
    if (!sent.gt_instance.empty()) {
      frame.gt_instance = InstancesFromImage(InstanceImage(sent.gt_instance, sent.width(), sent.height()), "loopback");
    }
    return frame;
  }

 private:
  RobotServer* server_;
};

}  // namespace objscan::ros_bridge
