#include "robot_server.h"

#include <string>

#include "objscan/common/error.h"
#include "objscan/navigation/occupancy_source.h"

namespace objscan::ros_bridge {
namespace {

// The grid as it was sent: the navigator takes it as its source gives it.
class SentGrid : public navigation::OccupancySource {
 public:
  explicit SentGrid(const navigation::OccupancyGrid2D& grid) : grid_(grid) {}
  navigation::OccupancyGrid2D Grid(double, double, double) const override { return grid_; }

 private:
  const navigation::OccupancyGrid2D& grid_;
};

}  // namespace

RobotServer::RobotServer(platform::Platform* robot) : robot_(robot) {}
RobotServer::~RobotServer() = default;

RobotState RobotServer::State() const {
  RobotState s;
  s.base = robot_->base();
  s.T_world_camera = robot_->T_world_camera();
  s.travel = robot_->travel();
  return s;
}

RobotResponse RobotServer::Serve(const RobotRequest& request) {
  RobotResponse response;
  response.id = request.id;
  const bool needs_map = request.kind == RequestKind::kCheckReach || request.kind == RequestKind::kMoveCamera;
  if (needs_map && (!navigator_ || request.map_revision != map_revision_)) {
    response.error = "request " + std::to_string(request.id) + " names map revision " +
                     std::to_string(request.map_revision) + ", the robot holds " +
                     (navigator_ ? "revision " + std::to_string(map_revision_) : std::string("no map"));
  } else if (request.kind != RequestKind::kHello && request.kind != RequestKind::kMap &&
             request.kind != RequestKind::kCapture && !request.T_world_camera.matrix().allFinite()) {
    response.error = "request " + std::to_string(request.id) + ": the camera pose is not finite";
  } else {
    try {
      Dispatch(request, &response);
    } catch (const std::exception& e) {  // a map the navigator rejects, a pose the robot rejects
      response.error = "request " + std::to_string(request.id) + ": " + OneLine(e.what());
    }
  }
  response.state = State();
  return response;
}

void RobotServer::Dispatch(const RobotRequest& request, RobotResponse* out) {
  RobotResponse& response = *out;
  switch (request.kind) {
    case RequestKind::kHello:
      response.world_name = robot_->world_name();
      response.intrinsics = robot_->intrinsics();
      break;
    case RequestKind::kMap: {
      const NavigationMap& m = request.map;
      navigator_ = std::make_unique<navigation::Navigator>(SentGrid(m.grid), m.robot_radius_m, m.robot_height_m,
                                                           m.options);
      map_revision_ = m.revision;
      break;
    }
    case RequestKind::kCheckReach: response.status = robot_->CheckReach(request.T_world_camera, *navigator_); break;
    case RequestKind::kMoveCamera: {
      const platform::Move move = robot_->MoveCamera(request.T_world_camera, *navigator_);
      response.status = move.status;
      response.path = move.path;
      response.T_world_camera_taken = move.T_world_camera;
      break;
    }
    case RequestKind::kTurnCamera: response.T_world_camera_taken = robot_->TurnCamera(request.T_world_camera); break;
    case RequestKind::kCapture: break;
  }
}

}  // namespace objscan::ros_bridge
