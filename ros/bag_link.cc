#include "bag_link.h"

#include <ros/serialization.h>

#include <boost/make_shared.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/String.h>
#include <tf2/buffer_core.h>
#include <tf2/exceptions.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "bag_reader.h"
#include "depth_image.h"
#include "objscan/common/error.h"
#include "pose_conversion.h"
#include "ros_messages.h"

namespace objscan::ros_bridge {
namespace {

// A message of the bag as its ROS type.
template <class T>
boost::shared_ptr<T> Deserialize(const BagMessage& m, const std::string& path) {
  auto msg = boost::make_shared<T>();
  try {
    ros::serialization::IStream stream(const_cast<std::uint8_t*>(m.data.data()), static_cast<std::uint32_t>(m.data.size()));
    ros::serialization::deserialize(stream, *msg);
  } catch (const ros::Exception& e) {
    throw InputError(path + ": a message on " + m.topic + " does not read as " + m.type + ": " + OneLine(e.what()));
  }
  return msg;
}

// Whether `topic` (as recorded, e.g. /ns/camera/depth/image) is `name` (relative) in any namespace.
bool IsTopic(const std::string& topic, const std::string& name) {
  return topic.size() >= name.size() + 1 && topic.compare(topic.size() - name.size(), name.size(), name) == 0 &&
         topic[topic.size() - name.size() - 1] == '/';
}

// A request as the scanner asks it again: without when it was asked.
std::string Comparable(RobotRequest request) {
  request.asked_stamp_ns = 0;
  return EncodeRequest(request);
}

}  // namespace

struct BagLink::Recording {
  std::map<std::uint64_t, std::string> requests;  // Comparable(request), by id
  std::map<std::uint64_t, RobotResponse> responses;
  // Per capture request, its depth image (the first stamped at or after the request), with its camera
  // info and instances.
  struct Frame {
    sensor_msgs::ImageConstPtr depth;
    sensor_msgs::CameraInfoConstPtr info;
    sensor_msgs::ImageConstPtr instance;
  };
  std::map<std::uint64_t, Frame> frames;
  tf2::BufferCore tf{ros::Duration(24 * 3600.0)};
  platform::CameraIntrinsics hello_intrinsics;
};

BagLink::BagLink(const std::string& bag_path, const std::string& world_frame, bool ground_truth)
    : recording_(std::make_unique<Recording>()),
      bag_path_(bag_path),
      world_frame_(world_frame),
      ground_truth_(ground_truth) {
  Recording& r = *recording_;
  // Capture requests in the order they were recorded: (id, when asked; 0 in a bag that does not say).
  std::vector<std::pair<std::uint64_t, std::uint64_t>> captures;
  std::map<ros::Time, sensor_msgs::CameraInfoConstPtr> infos;
  std::map<ros::Time, sensor_msgs::ImageConstPtr> instances;
  std::map<ros::Time, sensor_msgs::ImageConstPtr> depths;   // by stamp
  // Bags without the request's time: each image goes to the oldest capture recorded before it
  // still without one.
  std::vector<std::pair<std::uint64_t, sensor_msgs::ImageConstPtr>> depths_by_order;
  std::vector<std::uint64_t> waiting_captures;
  ReadBag(bag_path, [&](const BagMessage& m) {
    const std::string& topic = m.topic;
    if (IsTopic(topic, kRequestTopic) && m.type == "std_msgs/String") {
      const RobotRequest request = DecodeRequest(Deserialize<std_msgs::String>(m, bag_path)->data);
      r.requests[request.id] = Comparable(request);
      if (request.kind == RequestKind::kCapture) {
        captures.emplace_back(request.id, request.asked_stamp_ns);
        waiting_captures.push_back(request.id);
      }
    } else if (IsTopic(topic, kResponseTopic) && m.type == "std_msgs/String") {
      RobotResponse response = DecodeResponse(Deserialize<std_msgs::String>(m, bag_path)->data);
      r.responses[response.id] = std::move(response);
    } else if (IsTopic(topic, kDepthTopic) && m.type == "sensor_msgs/Image") {
      const auto msg = Deserialize<sensor_msgs::Image>(m, bag_path);
      depths.emplace(msg->header.stamp, msg);
      if (waiting_captures.empty()) return;  // a camera streams: frames nobody asked for
      depths_by_order.emplace_back(waiting_captures.front(), msg);
      waiting_captures.erase(waiting_captures.begin());
    } else if (IsTopic(topic, kInfoTopic) && m.type == "sensor_msgs/CameraInfo") {
      const auto msg = Deserialize<sensor_msgs::CameraInfo>(m, bag_path);
      infos[msg->header.stamp] = msg;
    } else if (IsTopic(topic, kInstanceTopic) && m.type == "sensor_msgs/Image") {
      const auto msg = Deserialize<sensor_msgs::Image>(m, bag_path);
      instances[msg->header.stamp] = msg;
    } else if ((topic == "/tf" || topic == "/tf_static") && m.type == "tf2_msgs/TFMessage") {
      const auto msg = Deserialize<tf2_msgs::TFMessage>(m, bag_path);
      for (const geometry_msgs::TransformStamped& t : msg->transforms) r.tf.setTransform(t, "bag", topic == "/tf_static");
    }
  });
  if (r.requests.empty() || r.responses.empty()) {
    throw InputError(bag_path + ": the bag holds no conversation with a robot (objscan/robot_request and "
                                "objscan/robot_response; record them with the camera topics and /tf, docs/ros.md)");
  }
  auto frame_of = [&](const sensor_msgs::ImageConstPtr& depth) {
    Recording::Frame f;
    f.depth = depth;
    const auto info = infos.find(depth->header.stamp);
    if (info != infos.end()) f.info = info->second;
    const auto instance = instances.find(depth->header.stamp);
    if (instance != instances.end()) f.instance = instance->second;
    return f;
  };
  const bool stamped = !captures.empty() && std::all_of(captures.begin(), captures.end(),
                                                         [](const auto& c) { return c.second != 0; });
  if (stamped) {
    // As objscan_ros takes them live: the first image stamped at or after the request.
    for (const auto& [id, asked_ns] : captures) {
      ros::Time asked;
      asked.fromNSec(asked_ns);
      const auto depth = depths.lower_bound(asked);
      if (depth != depths.end()) r.frames[id] = frame_of(depth->second);
    }
  } else {
    for (const auto& [id, depth] : depths_by_order) r.frames[id] = frame_of(depth);
  }
}

BagLink::~BagLink() = default;

RobotResponse BagLink::Call(const RobotRequest& request) {
  const Recording& r = *recording_;
  const auto recorded = r.requests.find(request.id);
  const std::string asked = Comparable(request);
  // A recorder connects to each topic on its own time and may miss the first requests (the hello
  // before it subscribed): their responses are taken as they are.
  if (recorded == r.requests.end() && r.responses.count(request.id) == 0) {
    throw LinkError("the bag holds no request " + std::to_string(request.id) + " (" + RequestKindName(request.kind) +
                    "): the recorded run ended before this one");
  }
  if (recorded != r.requests.end() && recorded->second != asked) {
    throw LinkError("request " + std::to_string(request.id) + " (" + RequestKindName(request.kind) +
                    ") differs from the recorded one: play a bag back with the seed, config and database it was "
                    "recorded with");
  }
  const auto response = r.responses.find(request.id);
  if (response == r.responses.end()) {
    throw LinkError("the bag holds no response to request " + std::to_string(request.id) + " (" +
                    RequestKindName(request.kind) + ")");
  }
  if (request.kind == RequestKind::kHello) recording_->hello_intrinsics = response->second.intrinsics;
  return response->second;
}

platform::DepthFrame BagLink::Capture(std::uint64_t request_id) {
  Recording& r = *recording_;
  RobotRequest request;
  request.id = request_id;
  request.kind = RequestKind::kCapture;
  const auto recorded = r.requests.find(request_id);
  if (recorded == r.requests.end() || recorded->second != Comparable(request)) {
    throw LinkError("capture request " + std::to_string(request_id) + " is not in the bag as a capture request");
  }
  const auto it = r.frames.find(request_id);
  if (it == r.frames.end() || !it->second.info || (ground_truth_ && !it->second.instance)) {
    throw LinkError("the bag holds no depth frame (with its camera info" +
                    std::string(ground_truth_ ? " and instances" : "") + ") after capture request " +
                    std::to_string(request_id));
  }
  const Recording::Frame& f = it->second;
  platform::DepthFrame frame = FrameFromMsgs(
      *f.depth, *f.info, ground_truth_ ? f.instance.get() : nullptr, r.hello_intrinsics,
      {bag_path_ + " " + kDepthTopic, bag_path_ + " " + kInfoTopic, bag_path_ + " " + kInstanceTopic});
  try {
    const geometry_msgs::TransformStamped t =
        r.tf.lookupTransform(world_frame_, f.depth->header.frame_id, f.depth->header.stamp);
    frame.T_world_camera =
        PoseFromTransform(FromTransformMsg(t.transform), "tf " + world_frame_ + " -> " + f.depth->header.frame_id);
  } catch (const tf2::TransformException& e) {
    throw LinkError("no camera pose in the bag's tf for the depth frame of capture request " +
                    std::to_string(request_id) + ": " + OneLine(e.what()));
  }
  return frame;
}

}  // namespace objscan::ros_bridge
