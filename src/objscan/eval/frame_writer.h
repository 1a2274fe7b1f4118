#pragma once
// `objscan run --save-frames`: the depth images the robot took, in the layout RGB-D SLAM tools read
// (TUM RGB-D): OUT/frames/depth/NNNNNN.png (16-bit, depth_scale units per metre, 0 = no depth),
// depth.txt ("timestamp depth/NNNNNN.png"), groundtruth.txt (T_world_camera per frame as
// "timestamp tx ty tz qx qy qz qw", camera x right, y down, z forward) and intrinsics.json.
#include <string>
#include <vector>

#include "objscan/scanning/run_record.h"
#include "objscan/platform/depth_frame.h"

namespace objscan::eval {

class FrameWriter {
 public:
  // TUM RGB-D's depth scale: 5000 units per metre (0.2 mm; up to 13.1 m).
  static constexpr double kDepthScale = 5000.0;

  // Creates `dir`/depth; throws InputError naming the folder when it cannot.
  explicit FrameWriter(const std::string& dir);

  // Writes one frame's depth image (atomically); keeps its pose and intrinsics for Finish.
  void Write(const platform::DepthFrame& frame);
  // Writes depth.txt, groundtruth.txt and intrinsics.json. Timestamps are the simulated times of the
  // run's views (trajectory.tum) when there is one view per frame, else the frame index.
  void Finish(const scanning::RunRecord& record) const;

  int frames() const { return static_cast<int>(poses_.size()); }

 private:
  std::string dir_;
  std::vector<geometry::Pose3> poses_;
  platform::CameraIntrinsics intrinsics_;
};

}  // namespace objscan::eval
