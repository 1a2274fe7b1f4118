#pragma once
// ROS 1 messages from and to the bridge's plain types (bridge/depth_image.h, pose_conversion.h), and
// the messages the node shows its scan with in RViz. The only place besides the two nodes that
// includes ROS headers.
#include <geometry_msgs/Transform.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include <vector>

#include "depth_image.h"
#include "objscan/geometry/pose.h"
#include "objscan/io/ply.h"
#include "objscan/platform/platform.h"
#include "pose_conversion.h"

namespace objscan::ros_bridge {

// The robot's topics, relative to the nodes' namespace (docs/ros.md).
constexpr char kRequestTopic[] = "objscan/robot_request";
constexpr char kResponseTopic[] = "objscan/robot_response";
constexpr char kDepthTopic[] = "camera/depth/image";
constexpr char kInfoTopic[] = "camera/depth/camera_info";
constexpr char kInstanceTopic[] = "camera/depth/gt_instance";

sensor_msgs::Image ToImageMsg(const ImageBuffer& image, const std_msgs::Header& header);
ImageBuffer FromImageMsg(const sensor_msgs::Image& msg);
sensor_msgs::CameraInfo ToCameraInfoMsg(const CameraInfoBuffer& info, const std_msgs::Header& header);
CameraInfoBuffer FromCameraInfoMsg(const sensor_msgs::CameraInfo& msg);
geometry_msgs::Transform ToTransformMsg(const TransformBuffer& transform);
TransformBuffer FromTransformMsg(const geometry_msgs::Transform& msg);

// Where a frame's three messages came from, named in errors (their topics, or a bag's).
struct FrameSources {
  std::string depth, info, instance;
};

// A depth frame from its image, camera info and (when not null) ground-truth instance image, as the
// robot sent them; the range limits from the robot's hello (CameraInfo has none). The pose is the
// caller's (tf). Throws InputError naming the source when they do not read or differ in size.
platform::DepthFrame FrameFromMsgs(const sensor_msgs::Image& depth, const sensor_msgs::CameraInfo& info,
                                   const sensor_msgs::Image* instance, const platform::CameraIntrinsics& hello,
                                   const FrameSources& sources);

// The labelled reconstruction: x y z (float32), object_id and category_id (int32, -1 = none) per point.
sensor_msgs::PointCloud2 LabelledCloudMsg(const std::vector<Eigen::Vector3f>& points,
                                          const std::vector<int>& object_id, const std::vector<int>& category_id,
                                          const std_msgs::Header& header);
// One arrow per view (the camera's optical axis), numbered in order; a DELETEALL first so views of
// an earlier run disappear.
visualization_msgs::MarkerArray ViewMarkers(const std::vector<geometry::Pose3>& views, const std_msgs::Header& header);
// The placed models (eval::PlacedModelsPly) as one coloured triangle list, their points where a
// model has no mesh.
visualization_msgs::MarkerArray ModelMarkers(const io::PlyData& models, const std_msgs::Header& header);

}  // namespace objscan::ros_bridge
