// objscan_ros: objscan's scan over ROS 1. The platform is a robot on the other end of topics
// (bridge/remote_platform.h): requests and responses as JSON text, depth frames as sensor_msgs/Image
// with CameraInfo and tf. The run is written as `objscan run` writes it (apps/objscan/run_scan.h),
// and shown as it goes: the labelled reconstruction, the planned views and the placed models.
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <tf2/exceptions.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "objscan/common/error.h"
#include "objscan/eval/run_output.h"
#include "objscan/io/scene_spec.h"
#include "objscan/scanning/scene_limits.h"
#include "objscan/scanning/system_config.h"
#include "bag_link.h"
#include "remote_platform.h"
#include "ros_messages.h"
#include "run_scan.h"

namespace objscan::ros_bridge {
namespace {

struct NodeArgs {
  std::string scene;  // ground truth for evaluation (optional)
  std::string db;
  std::string out = "objscan-out";
  std::uint64_t seed = 1;
  app::ConfigArgs config;
  bool quiet = false;
  bool save_frames = false;
  std::string world_frame = "world";
  double connect_timeout_s = 30.0;
  double request_timeout_s = 10.0;
  double frame_timeout_s = 10.0;
  std::string bag;  // play a recorded scan back instead of driving a robot
};

// The topics (ros_messages.h) are relative to the node's namespace: remap them as usual, name:=/other.

// A RobotLink over roscpp. Its subscriptions have their own callback queue, served only while a call
// waits, so nothing arrives between calls and messages are handled in order on this one thread.
class RosLink : public RobotLink {
 public:
  RosLink(const NodeArgs& args, bool ground_truth) : args_(args), ground_truth_(ground_truth), tf_listener_(tf_) {
    ros::NodeHandle nh;
    nh.setCallbackQueue(&queue_);
    const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
    request_pub_ = nh.advertise<std_msgs::String>(kRequestTopic, 1000);
    response_sub_ = nh.subscribe(kResponseTopic, 1000, &RosLink::OnResponse, this, hints);
    depth_sub_ = nh.subscribe(kDepthTopic, 10, &RosLink::OnDepth, this, hints);
    info_sub_ = nh.subscribe(kInfoTopic, 10, &RosLink::OnInfo, this, hints);
    if (ground_truth_) instance_sub_ = nh.subscribe(kInstanceTopic, 10, &RosLink::OnInstance, this, hints);
  }

  RobotResponse Call(const RobotRequest& request) override {
    if (request.kind == RequestKind::kHello) WaitForRobot();
    // A subscriber on the request topic may be a recorder while the robot is still connecting, and a
    // message sent before it connects is lost: the hello (which changes nothing) goes again each
    // second until answered. Any other request is sent once.
    const bool resend = request.kind == RequestKind::kHello;
    const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(args_.request_timeout_s);
    bool answered = false;
    while (!answered && ros::ok() && ros::WallTime::now() < until) {
      Publish(request);
      const double left_s = std::max(0.0, (until - ros::WallTime::now()).toSec());
      answered = SpinUntil(resend ? std::min(kHelloResendS, left_s) : left_s,
                           [&] { return responses_.count(request.id) > 0; });
      if (!resend) break;
    }
    if (!answered) {
      throw LinkError(std::string("no response to the ") + RequestKindName(request.kind) + " request on " +
                      response_sub_.getTopic() + " within " + Seconds(args_.request_timeout_s));
    }
    RobotResponse r = responses_.at(request.id);
    responses_.erase(request.id);
    if (request.kind == RequestKind::kHello) hello_intrinsics_ = r.intrinsics;
    return r;
  }

  platform::DepthFrame Capture(std::uint64_t request_id) override {
    const ros::Time asked = ros::Time::now();
    RobotRequest request;
    request.id = request_id;
    request.kind = RequestKind::kCapture;
    request.asked_stamp_ns = asked.toNSec();  // so a bag played back picks the same frame
    Publish(request);
    // The first depth image taken since the request, with its camera info (and ground truth).
    sensor_msgs::ImageConstPtr depth;
    const bool arrived = SpinUntil(args_.frame_timeout_s, [&] {
      while (!depth_.empty() && depth_.front()->header.stamp < asked) depth_.pop_front();
      if (depth_.empty()) return false;
      const ros::Time stamp = depth_.front()->header.stamp;
      if (!infos_.count(stamp) || (ground_truth_ && !instances_.count(stamp))) return false;
      depth = depth_.front();
      return true;
    });
    if (!arrived) {
      throw LinkError("no depth frame on " + depth_sub_.getTopic() + " (with its " + info_sub_.getTopic() +
                      (ground_truth_ ? " and " + instance_sub_.getTopic() : std::string()) + ") within " +
                      Seconds(args_.frame_timeout_s));
    }
    const ros::Time stamp = depth->header.stamp;
    depth_.pop_front();
    platform::DepthFrame frame =
        FrameFromMsgs(*depth, *infos_.at(stamp), ground_truth_ ? instances_.at(stamp).get() : nullptr,
                      hello_intrinsics_, {depth_sub_.getTopic(), info_sub_.getTopic(),
                       ground_truth_ ? instance_sub_.getTopic() : std::string()});
    try {
      const geometry_msgs::TransformStamped t = tf_.lookupTransform(args_.world_frame, depth->header.frame_id, stamp,
                                                                    ros::Duration(args_.frame_timeout_s));
      frame.T_world_camera = PoseFromTransform(FromTransformMsg(t.transform), "tf " + args_.world_frame + " -> " +
                                                                                  depth->header.frame_id);
    } catch (const tf2::TransformException& e) {
      throw LinkError("no camera pose in tf for the depth frame: " + OneLine(e.what()));
    }
    // Frames are taken one at a time: what is older is of no use any more.
    infos_.erase(infos_.begin(), infos_.upper_bound(stamp));
    instances_.erase(instances_.begin(), instances_.upper_bound(stamp));
    return frame;
  }

 private:
  static constexpr double kHelloResendS = 1.0;
  static std::string Seconds(double s) { return std::to_string(static_cast<int>(std::ceil(s))) + " s"; }

  void Publish(const RobotRequest& request) {
    std_msgs::String msg;
    msg.data = EncodeRequest(request);
    request_pub_.publish(msg);
  }

  // The robot's topics connected both ways, or a clear line naming what is missing.
  void WaitForRobot() {
    auto connected = [&] {
      return request_pub_.getNumSubscribers() > 0 && response_sub_.getNumPublishers() > 0 &&
             depth_sub_.getNumPublishers() > 0 && info_sub_.getNumPublishers() > 0 &&
             (!ground_truth_ || instance_sub_.getNumPublishers() > 0);
    };
    if (!SpinUntil(args_.connect_timeout_s, connected)) {
      throw LinkError("no robot on " + request_pub_.getTopic() + ", " + response_sub_.getTopic() + ", " +
                      depth_sub_.getTopic() + ", " + info_sub_.getTopic() +
                      (ground_truth_ ? ", " + instance_sub_.getTopic() : std::string()) + " within " +
                      Seconds(args_.connect_timeout_s) + " (is objscan_sim_ros or the robot's bridge running?)");
    }
  }

  // Serves this link's callbacks until `done` or the timeout (wall time; false then, or on shutdown).
  bool SpinUntil(double timeout_s, const std::function<bool()>& done) {
    const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(timeout_s);
    while (!done()) {
      if (!ros::ok() || ros::WallTime::now() > until) return false;
      queue_.callAvailable(ros::WallDuration(0.01));
    }
    return true;
  }

  void OnResponse(const std_msgs::String::ConstPtr& msg) {
    try {
      RobotResponse r = DecodeResponse(msg->data);
      responses_[r.id] = std::move(r);
    } catch (const InputError& e) {
      ROS_WARN("objscan_ros: ignoring a response: %s", e.what());
    }
  }
  void OnDepth(const sensor_msgs::ImageConstPtr& msg) { depth_.push_back(msg); }
  void OnInfo(const sensor_msgs::CameraInfoConstPtr& msg) { infos_[msg->header.stamp] = msg; }
  void OnInstance(const sensor_msgs::ImageConstPtr& msg) { instances_[msg->header.stamp] = msg; }

  const NodeArgs& args_;
  bool ground_truth_;
  ros::CallbackQueue queue_;
  ros::Publisher request_pub_;
  ros::Subscriber response_sub_, depth_sub_, info_sub_, instance_sub_;
  std::map<std::uint64_t, RobotResponse> responses_;
  std::deque<sensor_msgs::ImageConstPtr> depth_;
  std::map<ros::Time, sensor_msgs::CameraInfoConstPtr> infos_;
  std::map<ros::Time, sensor_msgs::ImageConstPtr> instances_;
  platform::CameraIntrinsics hello_intrinsics_;
  tf2_ros::Buffer tf_;
  tf2_ros::TransformListener tf_listener_;
};

// What the node shows while it scans (latched: RViz started later still sees the last state).
class ScanDisplay {
 public:
  ScanDisplay(const std::string& world_frame, const recognition::ModelDatabase& database)
      : world_frame_(world_frame), database_(database) {
    ros::NodeHandle nh;
    cloud_pub_ = nh.advertise<sensor_msgs::PointCloud2>("objscan/reconstruction", 1, true);
    views_pub_ = nh.advertise<visualization_msgs::MarkerArray>("objscan/views", 1, true);
    models_pub_ = nh.advertise<visualization_msgs::MarkerArray>("objscan/models", 1, true);
  }

  void Show(const scanning::Scanner& scanner, const scanning::RunRecord& record, bool finished) {
    std_msgs::Header header;
    header.frame_id = world_frame_;
    header.stamp = ros::Time::now();
    const geometry::PointCloud cloud = scanner.surface_map().AllPoints();
    std::vector<int> object_id, category_id;
    if (finished) {
      scanner.ElementObjects(&object_id, &category_id);
    } else {
      scanner.AnalysisElementObjects(&object_id);  // categories are named at the end
    }
    cloud_pub_.publish(LabelledCloudMsg(cloud.points, object_id, category_id, header));
    std::vector<geometry::Pose3> views;
    for (const auto& s : record.steps) views.push_back(s.T_world_camera);
    views_pub_.publish(ViewMarkers(views, header));
    if (finished) {
      models_pub_.publish(ModelMarkers(eval::PlacedModelsPly(record, database_, [](const std::string&) {}), header));
    }
  }

 private:
  std::string world_frame_;
  const recognition::ModelDatabase& database_;
  ros::Publisher cloud_pub_, views_pub_, models_pub_;
};

int RunNode(const NodeArgs& args) {
  const scanning::SystemConfig config = app::LoadRunConfig(args.config);
  // The scene is ground truth for evaluation only: the scan sees what the robot's camera sends.
  std::optional<world::Scene> scene;
  if (!args.scene.empty()) {
    scene = io::LoadScene(args.scene, config.scene);
    scanning::CheckSceneLimits(*scene, config, args.scene);
  }
  const app::RunDatabase database = app::LoadRunDatabase(args.db, args.scene, config, args.quiet);

  app::ScanRunInputs in;
  in.config = &config;
  in.database = &database;
  in.scene = scene ? &*scene : nullptr;
  in.seed = args.seed;
  in.out = args.out;
  in.quiet = args.quiet;
  in.save_frames = args.save_frames;
  in.program = "objscan_ros";

  // The scan over `robot`; a failed link keeps what was scanned and ends with exit code 3.
  auto scan = [&](RemotePlatform& robot, const char* failed) {
    in.scene_spec = args.scene.empty() ? robot.world_name() : args.scene;
    const int code = app::ScanAndWrite(in, &robot);
    if (robot.failure().empty()) return code;
    std::fprintf(stderr, "objscan_ros: error: %s, the run is written as far as it got (%s): %s\n", failed,
                 args.out.c_str(), robot.failure().c_str());
    return 3;
  };

  if (!args.bag.empty()) {
    // Played back from a bag: no robot, no master, nothing shown.
    BagLink link(args.bag, args.world_frame, scene.has_value());
    RemotePlatform robot(&link, config.robot);
    return scan(robot, "the bag's run and this one part");
  }

  // Without a master roscpp would wait for one for ever.
  if (!ros::master::check()) {
    throw LinkError("no ROS master at " + ros::master::getURI() + " (start roscore, or set ROS_MASTER_URI)");
  }
  RosLink link(args, scene.has_value());
  RemotePlatform robot(&link, config.robot);
  ScanDisplay display(args.world_frame, database.database);

  in.on_step = [&display](const scanning::Scanner& s, const scanning::RunRecord& r, bool finished) {
    display.Show(s, r, finished);
  };
  return scan(robot, "the robot link failed");
}

}  // namespace
}  // namespace objscan::ros_bridge

int main(int argc, char** argv) {
  using objscan::ros_bridge::NodeArgs;
  // ros::init takes its own arguments (remappings name:=other, __name, __ns) out of argv.
  ros::init(argc, argv, "objscan_ros");
  NodeArgs args;
  CLI::App app{"objscan_ros: objscan's object-aware scan driving a robot over ROS 1 (docs/ros.md)"};
  app.add_option("--scene", args.scene, "scene SPEC of the robot's world, ground truth for evaluation (metrics); none for a real room");
  app.add_option("--db", args.db, "model database file (default: the built-in one for --scene, as `objscan run`)");
  app.add_option("--out", args.out, "output folder (as `objscan run`)")->capture_default_str();
  app.add_option("--seed", args.seed, "the run's seed (run.json; the simulator's noise is seeded by objscan_sim_ros)")->capture_default_str();
  objscan::app::AddConfigOptions(&app, &args.config);
  app.add_flag("--quiet", args.quiet, "no progress output on stderr");
  app.add_flag("--save-frames", args.save_frames, "also write every depth image to OUT/frames");
  app.add_option("--world-frame", args.world_frame, "the tf frame the scan is built in")->capture_default_str();
  app.add_option("--connect-timeout-s", args.connect_timeout_s, "seconds to wait for the robot's topics")->capture_default_str();
  app.add_option("--request-timeout-s", args.request_timeout_s, "seconds to wait for a response (a move included)")->capture_default_str();
  app.add_option("--frame-timeout-s", args.frame_timeout_s, "seconds to wait for a depth frame")->capture_default_str();
  app.add_option("--bag", args.bag, "play back a scan recorded with rosbag (docs/ros.md) instead of driving a robot: "
                 "give the seed, config and database it was recorded with; no ROS master needed");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return objscan::app::ReportErrors("objscan_ros", [&args] { return objscan::ros_bridge::RunNode(args); });
}
