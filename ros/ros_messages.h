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
#include "pose_conversion.h"

namespace objscan::ros_bridge {

sensor_msgs::Image ToImageMsg(const ImageBuffer& image, const std_msgs::Header& header);
ImageBuffer FromImageMsg(const sensor_msgs::Image& msg);
sensor_msgs::CameraInfo ToCameraInfoMsg(const CameraInfoBuffer& info, const std_msgs::Header& header);
CameraInfoBuffer FromCameraInfoMsg(const sensor_msgs::CameraInfo& msg);
geometry_msgs::Transform ToTransformMsg(const TransformBuffer& transform);
TransformBuffer FromTransformMsg(const geometry_msgs::Transform& msg);

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
