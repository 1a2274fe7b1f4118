#pragma once
// The robot's side of the protocol (robot_protocol.h) over any platform::Platform: objscan's
// simulator served to a scanner in another process. It keeps the latest navigation map it was sent
// and builds the navigator the scanner planned on from it, so a check or a move is answered as in
// one process.
#include <cstdint>
#include <memory>

#include "objscan/platform/platform.h"
#include "robot_protocol.h"

namespace objscan::ros_bridge {

class RobotServer {
 public:
  // `robot` must outlive the server.
  explicit RobotServer(platform::Platform* robot);
  ~RobotServer();

  // Answers every request but kCapture (whose frame the caller takes with Capture and sends on its
  // image topics); a request it cannot serve gets a response with `error` set.
  RobotResponse Serve(const RobotRequest& request);
  platform::DepthFrame Capture() { return robot_->Capture(); }
  RobotState State() const;

 private:
  void Dispatch(const RobotRequest& request, RobotResponse* response);

  platform::Platform* robot_;
  std::uint64_t map_revision_ = 0;
  std::unique_ptr<navigation::Navigator> navigator_;  // of map_revision_; null before the first map
};

}  // namespace objscan::ros_bridge
