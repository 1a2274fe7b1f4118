#include "objscan/eval/frame_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "objscan/io/png.h"

namespace objscan::eval {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> DataLines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  }
  return lines;
}

platform::DepthFrame Frame(double yaw_rad, const Eigen::Vector3d& position, std::vector<float> depth_m) {
  platform::DepthFrame f;
  f.intrinsics.width_px = 3;
  f.intrinsics.height_px = 2;
  f.intrinsics.fx_px = f.intrinsics.fy_px = 2.0;
  f.intrinsics.cx_px = 1.0;
  f.intrinsics.cy_px = 0.5;
  f.T_world_camera = geometry::Pose3::Identity();
  f.T_world_camera.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  f.T_world_camera.translation() = position;
  f.depth_m = std::move(depth_m);
  return f;
}

// Two frames written and read back: depth at 5000 units per metre (no depth and depth beyond 16 bits
// both 0), one line per frame in depth.txt and groundtruth.txt at the views' simulated times, the
// poses as unit quaternions with qw >= 0, and the intrinsics.
TEST(FrameWriterTest, DepthImagesPosesAndIntrinsicsInTheTumLayout) {
  const fs::path dir = fs::temp_directory_path() / ("objscan_frames_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "depth");
  std::ofstream(dir / "depth" / "000007.png") << "left over from an earlier run";
  FrameWriter writer(dir.string());
  EXPECT_FALSE(fs::exists(dir / "depth" / "000007.png")) << "an earlier run's frames are removed";
  writer.Write(Frame(0.0, {1.0, 2.0, 1.2}, {1.0f, 0.0f, 2.5f, 13.2f, 0.5002f, 4.0f}));
  writer.Write(Frame(M_PI, {-1.0, 0.5, 1.2}, std::vector<float>(6, 3.0f)));
  scanning::RunRecord record;
  for (double t : {0.0, 1.5, 4.25}) {
    scanning::TrajectorySample s;
    s.time_s = t;
    s.view = t != 1.5;  // a pose the robot passed without taking a view
    record.trajectory.push_back(s);
  }
  writer.Finish(record);
  EXPECT_EQ(writer.frames(), 2);

  const io::Image16 first = io::ReadPng16((dir / "depth" / "000000.png").string());
  ASSERT_EQ(first.width, 3);
  ASSERT_EQ(first.height, 2);
  EXPECT_EQ(first.values, (std::vector<std::uint16_t>{5000, 0, 12500, 0, 2501, 20000}));
  EXPECT_EQ(io::ReadPng16((dir / "depth" / "000001.png").string()).values, std::vector<std::uint16_t>(6, 15000));

  EXPECT_EQ(DataLines(dir / "depth.txt"),
            (std::vector<std::string>{"0.000000 depth/000000.png", "4.250000 depth/000001.png"}));
  const std::vector<std::string> poses = DataLines(dir / "groundtruth.txt");
  ASSERT_EQ(poses.size(), 2u);
  double t, x, y, z, qx, qy, qz, qw;
  std::istringstream(poses[1]) >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
  EXPECT_DOUBLE_EQ(t, 4.25);
  EXPECT_NEAR(x, -1.0, 1e-6);
  EXPECT_NEAR(y, 0.5, 1e-6);
  EXPECT_NEAR(z, 1.2, 1e-6);
  EXPECT_NEAR(std::abs(qz), 1.0, 1e-6) << "half a turn about z";
  EXPECT_GE(qw, 0.0);
  EXPECT_NEAR(qx * qx + qy * qy + qz * qz + qw * qw, 1.0, 1e-6);

  std::ifstream in(dir / "intrinsics.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["width"], 3);
  EXPECT_EQ(j["height"], 2);
  EXPECT_DOUBLE_EQ(j["fx"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["cy"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["depth_scale"].get<double>(), 5000.0);
  EXPECT_EQ(j["frames"], 2);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace objscan::eval
