#include "ros_messages.h"

#include <cstring>
#include <string>

#include "objscan/common/error.h"

namespace objscan::ros_bridge {

sensor_msgs::Image ToImageMsg(const ImageBuffer& image, const std_msgs::Header& header) {
  sensor_msgs::Image msg;
  msg.header = header;
  msg.width = static_cast<std::uint32_t>(image.width);
  msg.height = static_cast<std::uint32_t>(image.height);
  msg.encoding = image.encoding;
  msg.is_bigendian = image.is_bigendian ? 1 : 0;
  msg.step = image.step_bytes;
  msg.data = image.data;
  return msg;
}

ImageBuffer FromImageMsg(const sensor_msgs::Image& msg) {
  ImageBuffer image;
  image.width = static_cast<int>(msg.width);
  image.height = static_cast<int>(msg.height);
  image.encoding = msg.encoding;
  image.is_bigendian = msg.is_bigendian != 0;
  image.step_bytes = msg.step;
  image.data = msg.data;
  return image;
}

sensor_msgs::CameraInfo ToCameraInfoMsg(const CameraInfoBuffer& info, const std_msgs::Header& header) {
  sensor_msgs::CameraInfo msg;
  msg.header = header;
  msg.width = static_cast<std::uint32_t>(info.width);
  msg.height = static_cast<std::uint32_t>(info.height);
  msg.distortion_model = "plumb_bob";
  msg.D = {0.0, 0.0, 0.0, 0.0, 0.0};
  std::copy(info.K.begin(), info.K.end(), msg.K.begin());
  std::copy(info.R.begin(), info.R.end(), msg.R.begin());
  std::copy(info.P.begin(), info.P.end(), msg.P.begin());
  return msg;
}

CameraInfoBuffer FromCameraInfoMsg(const sensor_msgs::CameraInfo& msg) {
  CameraInfoBuffer info;
  info.width = static_cast<int>(msg.width);
  info.height = static_cast<int>(msg.height);
  std::copy(msg.K.begin(), msg.K.end(), info.K.begin());
  std::copy(msg.R.begin(), msg.R.end(), info.R.begin());
  std::copy(msg.P.begin(), msg.P.end(), info.P.begin());
  return info;
}

geometry_msgs::Transform ToTransformMsg(const TransformBuffer& t) {
  geometry_msgs::Transform msg;
  msg.translation.x = t.translation_m[0];
  msg.translation.y = t.translation_m[1];
  msg.translation.z = t.translation_m[2];
  msg.rotation.x = t.rotation_xyzw[0];
  msg.rotation.y = t.rotation_xyzw[1];
  msg.rotation.z = t.rotation_xyzw[2];
  msg.rotation.w = t.rotation_xyzw[3];
  return msg;
}

TransformBuffer FromTransformMsg(const geometry_msgs::Transform& msg) {
  TransformBuffer t;
  t.translation_m = {msg.translation.x, msg.translation.y, msg.translation.z};
  t.rotation_xyzw = {msg.rotation.x, msg.rotation.y, msg.rotation.z, msg.rotation.w};
  return t;
}

platform::DepthFrame FrameFromMsgs(const sensor_msgs::Image& depth, const sensor_msgs::CameraInfo& info,
                                   const sensor_msgs::Image* instance, const platform::CameraIntrinsics& hello,
                                   const FrameSources& sources) {
  platform::DepthFrame frame;
  frame.depth_m = DepthMetresFromImage(FromImageMsg(depth), sources.depth);
  frame.intrinsics =
      IntrinsicsFromCameraInfo(FromCameraInfoMsg(info), hello.min_range_m, hello.max_range_m, sources.info);
  if (frame.depth_m.size() != static_cast<std::size_t>(frame.intrinsics.NumPixels())) {
    throw InputError(sources.depth + ": depth image and camera info differ in size");
  }
  if (instance != nullptr) frame.gt_instance = InstancesFromImage(FromImageMsg(*instance), sources.instance);
  return frame;
}

sensor_msgs::PointCloud2 LabelledCloudMsg(const std::vector<Eigen::Vector3f>& points,
                                          const std::vector<int>& object_id, const std::vector<int>& category_id,
                                          const std_msgs::Header& header) {
  sensor_msgs::PointCloud2 msg;
  msg.header = header;
  msg.height = 1;
  msg.width = static_cast<std::uint32_t>(points.size());
  const char* names[] = {"x", "y", "z", "object_id", "category_id"};
  for (std::uint32_t f = 0; f < 5; ++f) {
    sensor_msgs::PointField field;
    field.name = names[f];
    field.offset = 4 * f;
    field.datatype = f < 3 ? sensor_msgs::PointField::FLOAT32 : sensor_msgs::PointField::INT32;
    field.count = 1;
    msg.fields.push_back(field);
  }
  msg.is_bigendian = false;  // x86 and ARM robots alike; a reader on another machine swaps by this flag
  msg.point_step = 20;
  msg.row_step = msg.point_step * msg.width;
  msg.is_dense = true;
  msg.data.resize(static_cast<std::size_t>(msg.row_step));
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::uint8_t* p = msg.data.data() + i * msg.point_step;
    std::memcpy(p, points[i].data(), 12);
    const std::int32_t ids[2] = {i < object_id.size() ? object_id[i] : -1, i < category_id.size() ? category_id[i] : -1};
    std::memcpy(p + 12, ids, 8);
  }
  return msg;
}

visualization_msgs::MarkerArray ViewMarkers(const std::vector<geometry::Pose3>& views, const std_msgs::Header& header) {
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker clear;
  clear.header = header;
  clear.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(clear);
  for (std::size_t i = 0; i < views.size(); ++i) {
    visualization_msgs::Marker m;
    m.header = header;
    m.ns = "views";
    m.id = static_cast<int>(i);
    m.type = visualization_msgs::Marker::ARROW;
    m.action = visualization_msgs::Marker::ADD;
    m.pose.orientation.w = 1.0;
    const Eigen::Vector3d from = views[i].translation();
    const Eigen::Vector3d to = from + 0.3 * views[i].linear().col(2);  // 30 cm along the optical axis
    for (const Eigen::Vector3d& p : {from, to}) {
      geometry_msgs::Point q;
      q.x = p.x();
      q.y = p.y();
      q.z = p.z();
      m.points.push_back(q);
    }
    m.scale.x = 0.02;  // shaft diameter
    m.scale.y = 0.05;  // head diameter
    m.scale.z = 0.08;  // head length
    // The latest view stands out.
    const bool last = i + 1 == views.size();
    m.color.r = last ? 1.0f : 0.2f;
    m.color.g = last ? 0.4f : 0.5f;
    m.color.b = last ? 0.0f : 1.0f;
    m.color.a = 1.0f;
    array.markers.push_back(m);
  }
  return array;
}

visualization_msgs::MarkerArray ModelMarkers(const io::PlyData& models, const std_msgs::Header& header) {
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker clear;
  clear.header = header;
  clear.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(clear);
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = "models";
  m.id = 0;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = 1.0;
  m.color.a = 1.0f;
  auto add_vertex = [&](std::size_t v) {
    geometry_msgs::Point q;
    q.x = models.points[v].x();
    q.y = models.points[v].y();
    q.z = models.points[v].z();
    m.points.push_back(q);
    std_msgs::ColorRGBA c;
    c.a = 1.0f;
    if (v < models.colors.size()) {
      c.r = models.colors[v][0] / 255.0f;
      c.g = models.colors[v][1] / 255.0f;
      c.b = models.colors[v][2] / 255.0f;
    }
    m.colors.push_back(c);
  };
  if (!models.triangles.empty()) {
    m.type = visualization_msgs::Marker::TRIANGLE_LIST;
    for (const Eigen::Vector3i& t : models.triangles) {
      for (int k = 0; k < 3; ++k) add_vertex(static_cast<std::size_t>(t[k]));
    }
  } else {
    m.type = visualization_msgs::Marker::POINTS;
    m.scale.x = m.scale.y = 0.01;
    for (std::size_t v = 0; v < models.points.size(); ++v) add_vertex(v);
  }
  if (!m.points.empty()) array.markers.push_back(m);
  return array;
}

}  // namespace objscan::ros_bridge
