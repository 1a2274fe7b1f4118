// The scanner on a platform that is not objscan's simulator, in a program linked without the
// simulator library (tests/without_sim/CMakeLists.txt): the method needs nothing of sim/.
//
// The platform is a small analytic one: a 4 m x 3 m room (floor and 2.5 m walls, no ceiling) with
// one box in it, its depth frames cast in closed form, and a different body from the simulator's: a
// holonomic base carrying the camera straight above its centre (no arm), driving on the method's map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "objscan/geometry/aabb.h"
#include "objscan/navigation/occupancy_source.h"
#include "objscan/platform/platform.h"
#include "objscan/platform/testing/platform_contract.h"
#include "objscan/recognition/test_database.h"
#include "objscan/scanning/scanner.h"
#include "objscan/scanning/system_config.h"

namespace objscan {
namespace {

geometry::Aabb3 Box(const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m) {
  geometry::Aabb3 box;
  box.Extend(min_m);
  box.Extend(max_m);
  return box;
}

// Entry and exit distances of the ray p + t d through the box; false when it misses.
bool RayBox(const Eigen::Vector3d& p, const Eigen::Vector3d& d, const geometry::Aabb3& box, double* t_in,
            double* t_out) {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12) {
      if (p[a] < box.min_m[a] || p[a] > box.max_m[a]) return false;
      continue;
    }
    double t0 = (box.min_m[a] - p[a]) / d[a], t1 = (box.max_m[a] - p[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
  }
  if (lo > hi) return false;
  *t_in = lo;
  *t_out = hi;
  return true;
}

class BoxRoomPlatform : public platform::Platform {
 public:
  static constexpr double kWallHeightM = 2.5;

  explicit BoxRoomPlatform(const platform::BasePose& start) : base_(start) {
    intrinsics_.width_px = 160;
    intrinsics_.height_px = 120;
    intrinsics_.fx_px = intrinsics_.fy_px = 131.25;  // the default field of view at a quarter of the size
    intrinsics_.cx_px = 79.5;
    intrinsics_.cy_px = 59.5;
    camera_ = geometry::CameraPoseFromYawPitch(Eigen::Vector3d(start.xy_m.x(), start.xy_m.y(), 1.2), start.theta_rad,
                                               0.0);
  }

  std::string world_name() const override { return "box room"; }
  platform::CameraIntrinsics intrinsics() const override { return intrinsics_; }
  platform::BasePose base() const override { return base_; }
  geometry::Pose3 T_world_camera() const override { return camera_; }
  platform::TravelStats travel() const override { return travel_; }

  platform::DepthFrame Capture() override {
    platform::DepthFrame frame;
    frame.intrinsics = intrinsics_;
    frame.T_world_camera = camera_;
    frame.depth_m.assign(static_cast<std::size_t>(intrinsics_.NumPixels()), 0.f);
    const Eigen::Vector3d p = camera_.translation();
    const geometry::Aabb3 room = Box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(kRoomX, kRoomY, kWallHeightM));
    const geometry::Aabb3 box = Box(Eigen::Vector3d(2.6, 1.2, 0.0), Eigen::Vector3d(3.2, 1.8, 0.8));
    for (int v = 0; v < intrinsics_.height_px; ++v) {
      for (int u = 0; u < intrinsics_.width_px; ++u) {
        // With the ray's camera z = 1, the distance along it is the depth.
        const Eigen::Vector3d d = camera_.linear() * intrinsics_.RayCamera(u, v);
        double t_in = 0.0, t_out = 0.0, depth = std::numeric_limits<double>::infinity();
        // Leaving the room through the floor or a wall hits it; through the open top, nothing.
        if (RayBox(p, d, room, &t_in, &t_out) && (p + t_out * d).z() < kWallHeightM - 1e-9) depth = t_out;
        if (RayBox(p, d, box, &t_in, &t_out) && t_in > 0.0) depth = std::min(depth, t_in);
        if (depth >= intrinsics_.min_range_m && depth <= intrinsics_.max_range_m) {
          frame.depth_m[static_cast<std::size_t>(v) * intrinsics_.width_px + u] = static_cast<float>(depth);
        }
      }
    }
    captured_.push_back(camera_);
    return frame;
  }

  platform::ReachStatus CheckReach(const geometry::Pose3& T_world_camera,
                                   const navigation::Navigator& map) const override {
    navigation::Path2D path;
    return Plan(T_world_camera, map, &path);
  }

  platform::Move MoveCamera(const geometry::Pose3& T_world_camera, const navigation::Navigator& map) override {
    platform::Move move;
    move.status = Plan(T_world_camera, map, &move.path);
    if (!move.ok()) return move;
    double yaw = 0.0, pitch = 0.0;
    geometry::YawPitchOfCamera(T_world_camera, &yaw, &pitch);
    base_.xy_m = T_world_camera.translation().head<2>();
    base_.theta_rad = yaw;
    camera_ = geometry::CameraPoseFromYawPitch(T_world_camera.translation(), yaw, pitch);
    travel_.distance_m += move.path.length_m;
    travel_.time_s += move.path.length_m / 0.5;
    ++travel_.moves;
    move.T_world_camera = camera_;
    return move;
  }

  geometry::Pose3 TurnCamera(const geometry::Pose3& T_world_camera) override {
    double yaw = 0.0, pitch = 0.0;
    geometry::YawPitchOfCamera(T_world_camera, &yaw, &pitch);
    camera_ = geometry::CameraPoseFromYawPitch(
        Eigen::Vector3d(base_.xy_m.x(), base_.xy_m.y(), T_world_camera.translation().z()), yaw, pitch);
    travel_.time_s += 1.0;
    return camera_;
  }

  const std::vector<geometry::Pose3>& captured() const { return captured_; }

 private:
  static constexpr double kRoomX = 4.0, kRoomY = 3.0;

  // This body: the camera above the base centre at 0.3-1.8 m, pitch within [-70, 30] degrees; the base
  // drives to the camera's XY.
  platform::ReachStatus Plan(const geometry::Pose3& T_world_camera, const navigation::Navigator& map,
                             navigation::Path2D* path) const {
    const double z = T_world_camera.translation().z();
    if (z < 0.3 || z > 1.8) return platform::ReachStatus::kCameraHeightOutOfRange;
    double yaw = 0.0, pitch = 0.0;
    geometry::YawPitchOfCamera(T_world_camera, &yaw, &pitch);
    if (pitch < geometry::DegToRad(-70.0) - 1e-9 || pitch > geometry::DegToRad(30.0) + 1e-9) {
      return platform::ReachStatus::kPitchOutOfRange;
    }
    const Eigen::Vector2d goal = T_world_camera.translation().head<2>();
    if (!map.IsFree(goal)) return platform::ReachStatus::kNoFreeBase;
    Eigen::Vector2d from;
    if (!map.StartFrom(base_.xy_m, &from)) return platform::ReachStatus::kStartBlocked;
    *path = map.Plan(from, goal);
    return path->ok() ? platform::ReachStatus::kOk : platform::ReachStatus::kUnreachable;
  }

  platform::CameraIntrinsics intrinsics_;
  platform::BasePose base_;
  geometry::Pose3 camera_;
  platform::TravelStats travel_;
  std::vector<geometry::Pose3> captured_;
};

// The room's occupancy as the platform's contract test needs a map: floor inside the walls, the box.
class BoxRoomOccupancy : public navigation::OccupancySource {
 public:
  navigation::OccupancyGrid2D Grid(double min_z_m, double max_z_m, double cell_size_m) const override {
    navigation::OccupancyGrid2D grid = navigation::OccupancyGrid2D::Covering(
        Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(4.5, 3.5), cell_size_m, navigation::CellState::kOccupied);
    for (int iy = 0; iy < grid.height; ++iy) {
      for (int ix = 0; ix < grid.width; ++ix) {
        const Eigen::Vector2d c = grid.CellCenter(ix, iy);
        const bool in_room = c.x() > 0.0 && c.x() < 4.0 && c.y() > 0.0 && c.y() < 3.0;
        const bool in_box = c.x() > 2.6 - 0.5 * cell_size_m && c.x() < 3.2 + 0.5 * cell_size_m &&
                            c.y() > 1.2 - 0.5 * cell_size_m && c.y() < 1.8 + 0.5 * cell_size_m && min_z_m < 0.8;
        if (in_room && !in_box && max_z_m > 0.0) grid.cells[grid.Index(ix, iy)] = navigation::CellState::kFree;
      }
    }
    return grid;
  }
};

TEST(ScannerWithoutSimTest, TheTestPlatformKeepsThePlatformContract) {
  platform::BasePose start;
  start.xy_m = Eigen::Vector2d(1.0, 1.0);
  BoxRoomPlatform room(start);
  const BoxRoomOccupancy occupancy;
  const navigation::Navigator map(occupancy, 0.25, 1.8);
  const geometry::Pose3 reachable =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(2.0, 2.4, 1.2), -0.3, geometry::DegToRad(-20));
  const geometry::Pose3 on_the_box =
      geometry::CameraPoseFromYawPitch(Eigen::Vector3d(2.9, 1.5, 1.2), 0.0, geometry::DegToRad(-20));
  platform::testing::ExpectPlatformContract(&room, map, reachable, on_the_box);
}

TEST(ScannerWithoutSimTest, ScansFromWhereThePlatformIsAndSeesOnlyItsFrames) {
  scanning::SystemConfig config;
  config.scanner.max_steps = 60;  // the room takes about ten
  config.scanner.threads = 1;
  const recognition::ModelDatabase database = recognition::BuildDatabaseFromScans(
      recognition::testing::ShapeModels(0.01), recognition::testing::SmallDatabaseOptions());
  platform::BasePose start;
  start.xy_m = Eigen::Vector2d(1.0, 1.0);
  start.theta_rad = 0.3;
  BoxRoomPlatform room(start);
  scanning::Scanner scanner(config, &room, database, /*seed=*/7);
  const scanning::RunRecord& record = scanner.Run();

  EXPECT_EQ(record.scene, "box room");
  EXPECT_EQ(record.seed, 7u);
  EXPECT_EQ(record.terminated, scanning::Termination::kDone);
  ASSERT_FALSE(record.trajectory.empty());
  // The scan starts where the platform stands, heading where it heads.
  EXPECT_EQ(record.trajectory.front().x_m, 1.0);
  EXPECT_EQ(record.trajectory.front().y_m, 1.0);
  EXPECT_EQ(record.trajectory.front().theta_rad, 0.3);
  // Every view is a frame the platform took, from the pose it took it at.
  ASSERT_EQ(static_cast<std::size_t>(record.views), room.captured().size());
  std::size_t view = 0;
  for (const auto& sample : record.trajectory) {
    if (!sample.view) continue;
    ASSERT_LT(view, room.captured().size());
    EXPECT_TRUE(sample.T_world_camera.isApprox(room.captured()[view], 1e-12)) << "view " << view;
    ++view;
  }
  EXPECT_EQ(view, room.captured().size());
  // It drove the base through the platform, which accounts the travel.
  EXPECT_GT(room.travel().moves, 0);
  EXPECT_DOUBLE_EQ(record.travel_m, room.travel().distance_m);
  // What it mapped is this room: the floor at z = 0 (within a voxel), the 12 m2 explored (plus at most
  // three 5 cm navigation cells of wall along the 14 m of walls), and one object, on the box.
  ASSERT_TRUE(record.structure.floor_height_m.has_value());
  EXPECT_NEAR(*record.structure.floor_height_m, 0.0, config.surface_map.voxel_size_m);
  const double cell_m = config.navigation.cell_size_m;
  EXPECT_GT(record.explored_area_m2, 12.0 - 14.0 * cell_m);
  EXPECT_LT(record.explored_area_m2, 12.0 + 14.0 * 3.0 * cell_m);
  ASSERT_EQ(record.objects.size(), 1u);
  const Eigen::Vector2d model_xy = record.objects[0].T_world_model.translation().head<2>();
  EXPECT_LT((model_xy - Eigen::Vector2d(2.9, 1.5)).norm(), 0.3) << model_xy.transpose();
}

}  // namespace
}  // namespace objscan
