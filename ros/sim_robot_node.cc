// objscan_sim_ros: objscan's simulator (sim::SimulatedRobot in a scene) served over ROS 1, the robot
// end of objscan_ros's topics: it answers requests (bridge/robot_server.h), renders a depth frame on
// each capture request and publishes it with its camera info, the ground-truth instances and the
// camera's and base's tf; after a move, the base's path (for RViz).
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "objscan/common/error.h"
#include "objscan/io/scene_spec.h"
#include "objscan/scanning/scene_limits.h"
#include "objscan/scanning/system_config.h"
#include "objscan/sim/simulated_robot.h"
#include "robot_server.h"
#include "ros_messages.h"
#include "run_scan.h"

namespace objscan::ros_bridge {
namespace {

struct SimArgs {
  std::string scene = "procedural:bedroom:1";
  std::uint64_t seed = 1;
  app::ConfigArgs config;
  std::string world_frame = "world";
  std::string base_frame = "base_link";
  std::string camera_frame = "camera_depth_optical_frame";
  int min_image_subscribers = 1;
  double subscriber_timeout_s = 30.0;
  bool ground_truth = true;
  int silent_after_requests = 0;
};

class SimNode {
 public:
  SimNode(const SimArgs& args, platform::Platform* robot) : args_(args), server_(robot) {
    ros::NodeHandle nh;
    const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
    response_pub_ = nh.advertise<std_msgs::String>(kResponseTopic, 1000);
    depth_pub_ = nh.advertise<sensor_msgs::Image>(kDepthTopic, 10);
    info_pub_ = nh.advertise<sensor_msgs::CameraInfo>(kInfoTopic, 10);
    if (args_.ground_truth) instance_pub_ = nh.advertise<sensor_msgs::Image>(kInstanceTopic, 10);
    path_pub_ = nh.advertise<nav_msgs::Path>("objscan/base_path", 10, true);
    // /tf through a publisher of our own (what tf2_ros::TransformBroadcaster does), so that its
    // subscribers can be counted before the scan starts.
    tf_pub_ = nh.advertise<tf2_msgs::TFMessage>("/tf", 100);
    request_sub_ = nh.subscribe(kRequestTopic, 1000, &SimNode::OnRequest, this, hints);
    PublishPose(ros::Time::now());
  }

 private:
  void OnRequest(const std_msgs::String::ConstPtr& msg) {
    // A robot that falls silent, to show what objscan_ros does then (tests/ros/test_ros_e2e.py).
    if (args_.silent_after_requests > 0 && ++requests_ > args_.silent_after_requests) return;
    RobotRequest request;
    try {
      request = DecodeRequest(msg->data);
    } catch (const InputError& e) {
      ROS_ERROR("objscan_sim_ros: %s", e.what());
      return;
    }
    if (request.kind == RequestKind::kCapture) {
      Capture();
      return;
    }
    if (request.kind == RequestKind::kHello) WaitForSubscribers();
    const RobotResponse response = server_.Serve(request);
    if (!response.error.empty()) ROS_ERROR("objscan_sim_ros: %s", response.error.c_str());
    if (request.kind == RequestKind::kMoveCamera && response.status == platform::ReachStatus::kOk) {
      PublishPath(response.path);
    }
    if (request.kind == RequestKind::kMoveCamera || request.kind == RequestKind::kTurnCamera) {
      PublishPose(ros::Time::now());
    }
    std_msgs::String out;
    out.data = EncodeResponse(response);
    response_pub_.publish(out);
  }

  // A recorder (rosbag) listening beside objscan_ros gets the whole scan only when it is connected
  // to every topic the robot publishes before the first answer: each connects on its own time
  // (a bag once missed the hello's response this way), so the scan starts once each of them has
  // enough subscribers.
  void WaitForSubscribers() {
    std::vector<const ros::Publisher*> topics = {&response_pub_, &tf_pub_, &info_pub_, &depth_pub_};
    if (args_.ground_truth) topics.push_back(&instance_pub_);
    auto fewest = [&] {
      const ros::Publisher* least = topics.front();
      for (const ros::Publisher* p : topics) {
        if (p->getNumSubscribers() < least->getNumSubscribers()) least = p;
      }
      return least;
    };
    const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(args_.subscriber_timeout_s);
    while (ros::ok() && static_cast<int>(fewest()->getNumSubscribers()) < args_.min_image_subscribers &&
           ros::WallTime::now() < until) {
      ros::WallDuration(0.01).sleep();
    }
    const ros::Publisher* least = fewest();
    if (static_cast<int>(least->getNumSubscribers()) < args_.min_image_subscribers) {
      ROS_WARN("objscan_sim_ros: %d of %d subscribers on %s after %.0f s; serving anyway", least->getNumSubscribers(),
               args_.min_image_subscribers, least->getTopic().c_str(), args_.subscriber_timeout_s);
    }
  }

  void Capture() {
    const platform::DepthFrame frame = server_.Capture();
    std_msgs::Header header;
    header.stamp = ros::Time::now();
    header.frame_id = args_.camera_frame;
    // The pose first: a listener looks it up for the image's stamp.
    PublishPose(header.stamp);
    info_pub_.publish(ToCameraInfoMsg(CameraInfoFromIntrinsics(frame.intrinsics), header));
    if (args_.ground_truth) {
      instance_pub_.publish(ToImageMsg(InstanceImage(frame.gt_instance, frame.width(), frame.height()), header));
    }
    depth_pub_.publish(ToImageMsg(DepthImageFromMetres(frame.depth_m, frame.width(), frame.height()), header));
  }

  void PublishPose(const ros::Time& stamp) {
    const RobotState state = server_.State();
    geometry_msgs::TransformStamped base, camera;
    base.header.stamp = camera.header.stamp = stamp;
    base.header.frame_id = camera.header.frame_id = args_.world_frame;
    base.child_frame_id = args_.base_frame;
    base.transform = ToTransformMsg(TransformFromBase(state.base));
    // The camera straight from the world frame: one transform, nothing composed on the way.
    camera.child_frame_id = args_.camera_frame;
    camera.transform = ToTransformMsg(TransformFromPose(state.T_world_camera));
    tf2_msgs::TFMessage msg;
    msg.transforms = {base, camera};
    tf_pub_.publish(msg);
  }

  void PublishPath(const navigation::Path2D& path) {
    nav_msgs::Path msg;
    msg.header.stamp = ros::Time::now();
    msg.header.frame_id = args_.world_frame;
    for (const Eigen::Vector2d& w : path.waypoints) {
      geometry_msgs::PoseStamped p;
      p.header = msg.header;
      p.pose.position.x = w.x();
      p.pose.position.y = w.y();
      p.pose.orientation.w = 1.0;
      msg.poses.push_back(p);
    }
    path_pub_.publish(msg);
  }

  const SimArgs& args_;
  int requests_ = 0;
  RobotServer server_;
  ros::Publisher response_pub_, depth_pub_, info_pub_, instance_pub_, path_pub_, tf_pub_;
  ros::Subscriber request_sub_;
};

int RunSim(const SimArgs& args) {
  const scanning::SystemConfig config = app::LoadRunConfig(args.config);
  const world::Scene scene = io::LoadScene(args.scene, config.scene);
  scanning::CheckSceneLimits(scene, config, args.scene);
  // Put down as `objscan run` puts it down, with the same seed: the same robot in the same room.
  sim::SimulatedRobot robot(scene, config.sensor, config.robot, config.navigation, args.seed);
  SimNode node(args, &robot);
  ros::spin();
  return 0;
}

}  // namespace
}  // namespace objscan::ros_bridge

int main(int argc, char** argv) {
  using objscan::ros_bridge::SimArgs;
  ros::init(argc, argv, "objscan_sim_ros");
  SimArgs args;
  CLI::App app{"objscan_sim_ros: objscan's simulator as a robot on ROS 1, for objscan_ros (docs/ros.md)"};
  app.add_option("--scene", args.scene, "scene SPEC (as `objscan run --scene`)")->capture_default_str();
  app.add_option("--seed", args.seed, "seed of the sensor noise (as `objscan run --seed`)")->capture_default_str();
  objscan::app::AddConfigOptions(&app, &args.config);
  app.add_option("--world-frame", args.world_frame, "tf frame of the scene")->capture_default_str();
  app.add_option("--base-frame", args.base_frame, "tf frame of the robot's base")->capture_default_str();
  app.add_option("--camera-frame", args.camera_frame, "tf frame of the depth camera (optical: z forward)")->capture_default_str();
  app.add_option("--min-image-subscribers", args.min_image_subscribers,
                 "wait for this many subscribers on each topic the robot publishes (images, camera info, /tf, "
                 "responses) before the scan starts (2 with a recorder)")
      ->capture_default_str();
  app.add_option("--subscriber-timeout-s", args.subscriber_timeout_s, "seconds to wait for them")->capture_default_str();
  app.add_option("--silent-after-requests", args.silent_after_requests,
                 "answer this many requests, then none (to test objscan_ros's timeouts; 0 = always answer)")
      ->capture_default_str();
  app.add_option("--ground-truth", args.ground_truth, "publish ground-truth instance images (evaluation)")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return objscan::app::ReportErrors("objscan_sim_ros", [&args] { return objscan::ros_bridge::RunSim(args); });
}
