#include "remote_platform.h"

namespace objscan::ros_bridge {
namespace {

// Metres, and the Frobenius norm of rotation differences: far above a quaternion's rounding (1e-16)
// and far below any motion.
constexpr double kSamePoseTolerance = 1e-9;

bool SameGrid(const navigation::OccupancyGrid2D& a, const navigation::OccupancyGrid2D& b) {
  return a.cell_size_m == b.cell_size_m && a.origin_m == b.origin_m && a.width == b.width && a.height == b.height &&
         a.cells == b.cells;
}

bool SameOptions(const navigation::NavigatorOptions& a, const navigation::NavigatorOptions& b) {
  return a.cell_size_m == b.cell_size_m && a.min_obstacle_height_m == b.min_obstacle_height_m &&
         a.smooth_path == b.smooth_path && a.start_escape_m == b.start_escape_m;
}

}  // namespace

RemotePlatform::RemotePlatform(RobotLink* link, const platform::RobotOptions& body) : link_(link), body_(body) {
  RobotRequest hello;
  hello.kind = RequestKind::kHello;
  hello.id = next_id_++;
  const RobotResponse r = link_->Call(hello);  // no robot, no scan: the LinkError goes to the caller
  if (!r.error.empty()) throw LinkError("the robot refused the greeting: " + r.error);
  world_name_ = r.world_name;
  intrinsics_ = r.intrinsics;
  state_ = r.state;
}

std::optional<RobotResponse> RemotePlatform::Call(RobotRequest request) const {
  if (!failure_.empty()) return std::nullopt;
  request.id = next_id_++;
  try {
    RobotResponse r = link_->Call(request);
    if (!r.error.empty()) {
      failure_ = std::string("the robot could not serve a ") + RequestKindName(request.kind) + " request: " + r.error;
      return std::nullopt;
    }
    state_ = r.state;
    return r;
  } catch (const LinkError& e) {
    failure_ = e.what();
    return std::nullopt;
  }
}

bool RemotePlatform::SendMap(const navigation::Navigator& map) const {
  if (map_revision_ > 0 && SameGrid(map.grid(), sent_grid_) && SameOptions(map.options(), sent_options_)) return true;
  RobotRequest request;
  request.kind = RequestKind::kMap;
  request.map.revision = map_revision_ + 1;
  request.map.grid = map.grid();
  request.map.robot_radius_m = body_.base_radius_m;
  request.map.robot_height_m = body_.height_m;
  request.map.options = map.options();
  if (!Call(request)) return false;
  map_revision_ = request.map.revision;
  sent_grid_ = map.grid();
  sent_options_ = map.options();
  return true;
}

platform::DepthFrame RemotePlatform::Capture() {
  if (failure_.empty()) {
    try {
      platform::DepthFrame frame = link_->Capture(next_id_++);
      // The robot reported its camera pose in full (robot_protocol.h); tf carries it as a rounded
      // quaternion. Where the two agree, the camera has not moved since and the exact pose is used,
      // so that a run over a link decides as one in a single process.
      const geometry::Pose3& reported = state_.T_world_camera;
      if ((frame.T_world_camera.translation() - reported.translation()).norm() < kSamePoseTolerance &&
          (frame.T_world_camera.linear() - reported.linear()).norm() < kSamePoseTolerance) {
        frame.T_world_camera = reported;
      }
      return frame;
    } catch (const LinkError& e) {
      failure_ = e.what();
    }
  }
  // Nothing seen: the scanner learns nothing from here on and comes to a stop.
  platform::DepthFrame frame;
  frame.intrinsics = intrinsics_;
  frame.T_world_camera = state_.T_world_camera;
  frame.depth_m.assign(static_cast<std::size_t>(intrinsics_.NumPixels()), 0.f);
  return frame;
}

platform::ReachStatus RemotePlatform::CheckReach(const geometry::Pose3& T_world_camera,
                                                 const navigation::Navigator& map) const {
  if (!SendMap(map)) return platform::ReachStatus::kUnreachable;
  RobotRequest request;
  request.kind = RequestKind::kCheckReach;
  request.T_world_camera = T_world_camera;
  request.map_revision = map_revision_;
  const std::optional<RobotResponse> r = Call(request);
  return r ? r->status : platform::ReachStatus::kUnreachable;
}

platform::Move RemotePlatform::MoveCamera(const geometry::Pose3& T_world_camera, const navigation::Navigator& map) {
  platform::Move move;
  move.status = platform::ReachStatus::kUnreachable;
  if (!SendMap(map)) return move;
  RobotRequest request;
  request.kind = RequestKind::kMoveCamera;
  request.T_world_camera = T_world_camera;
  request.map_revision = map_revision_;
  const std::optional<RobotResponse> r = Call(request);
  if (!r) return move;
  move.status = r->status;
  if (move.ok()) {
    move.path = r->path;
    move.T_world_camera = r->T_world_camera_taken;
  }
  return move;
}

geometry::Pose3 RemotePlatform::TurnCamera(const geometry::Pose3& T_world_camera) {
  RobotRequest request;
  request.kind = RequestKind::kTurnCamera;
  request.T_world_camera = T_world_camera;
  const std::optional<RobotResponse> r = Call(request);
  return r ? r->T_world_camera_taken : state_.T_world_camera;
}

}  // namespace objscan::ros_bridge
