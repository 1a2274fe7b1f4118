#include "objscan/eval/frame_writer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>

#include "objscan/common/error.h"
#include "objscan/io/atomic_file.h"
#include "objscan/io/png.h"

namespace objscan::eval {

FrameWriter::FrameWriter(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  // The folder is this writer's alone: frames of an earlier run there would mix with this one's.
  std::filesystem::remove_all(dir, ec);
  if (ec) throw InputError(dir + ": cannot replace the frames folder (" + ec.message() + ")");
  std::filesystem::create_directories(std::filesystem::path(dir) / "depth", ec);
  if (ec) throw InputError(dir + ": cannot create the frames folder (" + ec.message() + ")");
}

void FrameWriter::Write(const platform::DepthFrame& frame) {
  std::vector<std::uint16_t> depth(frame.depth_m.size(), 0);
  for (std::size_t i = 0; i < depth.size(); ++i) {
    const double d = static_cast<double>(frame.depth_m[i]) * kDepthScale;
    // Invalid (0) and beyond what 16 bits hold stay 0: no depth.
    if (frame.depth_m[i] > 0.f && d < 65535.5) depth[i] = static_cast<std::uint16_t>(std::lround(d));
  }
  char name[32];
  std::snprintf(name, sizeof(name), "depth/%06d.png", frames());
  io::WritePng16(dir_ + "/" + name, frame.width(), frame.height(), depth);
  poses_.push_back(frame.T_world_camera);
  intrinsics_ = frame.intrinsics;
}

void FrameWriter::Finish(const scanning::RunRecord& record) const {
  std::vector<double> times;
  for (const auto& t : record.trajectory) {
    if (t.view) times.push_back(t.time_s);
  }
  const bool view_times = times.size() == poses_.size();
  std::ostringstream depth_txt, poses_txt;
  depth_txt << "# objscan depth images (TUM RGB-D layout): timestamp filename\n";
  poses_txt << "# objscan T_world_camera per depth image, camera x right y down z forward\n"
            << "# timestamp tx ty tz qx qy qz qw\n";
  char line[256];
  for (std::size_t k = 0; k < poses_.size(); ++k) {
    const double t = view_times ? times[k] : static_cast<double>(k);
    std::snprintf(line, sizeof(line), "%.6f depth/%06zu.png\n", t, k);
    depth_txt << line;
    Eigen::Quaterniond q(poses_[k].linear());
    q.normalize();
    if (q.w() < 0.0) q.coeffs() = -q.coeffs();
    const Eigen::Vector3d p = poses_[k].translation();
    std::snprintf(line, sizeof(line), "%.6f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", t, p.x(), p.y(), p.z(), q.x(),
                  q.y(), q.z(), q.w());
    poses_txt << line;
  }
  io::WriteFileAtomically(dir_ + "/depth.txt", depth_txt.str());
  io::WriteFileAtomically(dir_ + "/groundtruth.txt", poses_txt.str());
  const nlohmann::json j = {{"width", intrinsics_.width_px},
                            {"height", intrinsics_.height_px},
                            {"fx", intrinsics_.fx_px},
                            {"fy", intrinsics_.fy_px},
                            {"cx", intrinsics_.cx_px},
                            {"cy", intrinsics_.cy_px},
                            {"depth_scale", kDepthScale},
                            {"min_range_m", intrinsics_.min_range_m},
                            {"max_range_m", intrinsics_.max_range_m},
                            {"frames", poses_.size()},
                            {"timestamps", view_times ? "simulated seconds of the views" : "frame index"}};
  io::WriteFileAtomically(dir_ + "/intrinsics.json", j.dump(2) + "\n");
}

}  // namespace objscan::eval
