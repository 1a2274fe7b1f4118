#include "objscan/render/depth_camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "objscan/common/error.h"
#include "objscan/geometry/mesh.h"
#include "objscan/render/depth_noise.h"

namespace objscan::render {
namespace {

using platform::CameraIntrinsics;
using platform::DepthFrame;

constexpr std::int32_t kWallId = 7;
constexpr std::int32_t kBoxId = 3;
constexpr std::int32_t kFloorId = 9;

// A wall whose front face is the plane x = distance_m (large enough to fill the image).
world::SceneObject Wall(double distance_m) {
  world::SceneObject wall;
  wall.instance_id = kWallId;
  wall.category = world::Category::kWall;
  wall.mesh = geometry::MakeBox(Eigen::Vector3d(distance_m, -50, -50), Eigen::Vector3d(distance_m + 0.1, 50, 50));
  return wall;
}

world::Scene WallScene(double distance_m) {
  world::Scene scene("wall");
  scene.Add(Wall(distance_m));
  return scene;
}

// Camera at the origin looking along +X.
geometry::Pose3 LookAlongX() { return geometry::CameraPoseFromYawPitch(Eigen::Vector3d::Zero(), 0.0, 0.0); }

SensorOptions NoiseOff() {
  SensorOptions o;
  o.noise = false;
  return o;
}

TEST(DepthCameraTest, FacingAPlaneDepthIsExactWithNoiseOff) {
  for (double distance : {0.6, 1.0, 2.0, 3.0, 3.9}) {
    const DepthCamera camera(WallScene(distance), NoiseOff());
    const DepthFrame frame = camera.Render(LookAlongX(), nullptr);
    ASSERT_EQ(frame.depth_m.size(), 640u * 480u);
    double max_error = 0.0;
    for (std::size_t i = 0; i < frame.depth_m.size(); ++i) {
      ASSERT_GT(frame.depth_m[i], 0.f) << "pixel " << i << " at " << distance << " m";
      max_error = std::max(max_error, std::abs(frame.depth_m[i] - distance));
      ASSERT_EQ(frame.gt_instance[i], kWallId);
      ASSERT_NEAR(frame.gt_normal_world[i].x(), -1.f, 1e-6);
    }
    EXPECT_LE(max_error, 1e-4) << distance;
    EXPECT_EQ(frame.NumValid(), frame.depth_m.size());
    // Back-projection lands on the plane.
    EXPECT_NEAR(frame.PointWorld(0, 0).x(), distance, 1e-4);
    EXPECT_NEAR(frame.PointWorld(639, 479).x(), distance, 1e-4);
  }
}

TEST(DepthCameraTest, TiltedPlaneMatchesAnalyticDepth) {
  // Plane through (2, 0, 0) with normal n (tilted 35 deg about Z and 20 deg about Y).
  const Eigen::Vector3d n = (Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitY()) * Eigen::Vector3d(-1, 0, 0))
                                .normalized();
  world::Scene scene("tilted");
  world::SceneObject plane = Wall(0.0);
  plane.mesh = geometry::MakeBox(Eigen::Vector3d(0, -30, -30), Eigen::Vector3d(0.1, 30, 30));
  // Rotate the slab so its front face normal (-X) becomes n, and put it through (2, 0, 0).
  plane.T_world_object.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(-1, 0, 0), n).toRotationMatrix();
  plane.T_world_object.translation() = Eigen::Vector3d(2, 0, 0);
  scene.Add(plane);
  SensorOptions options = NoiseOff();
  options.max_range_m = 20.0;
  const DepthCamera camera(scene, options);
  const geometry::Pose3 T = geometry::CameraPoseFromYawPitch(Eigen::Vector3d(0, 0, 0.3), 0.1, -0.05);
  const DepthFrame frame = camera.Render(T, nullptr);
  const CameraIntrinsics& K = frame.intrinsics;
  const double c = n.dot(Eigen::Vector3d(2, 0, 0));
  for (int v = 0; v < K.height_px; v += 7) {
    for (int u = 0; u < K.width_px; u += 5) {
      const Eigen::Vector3d d = T.linear() * K.RayCamera(u, v);  // camera z = 1
      const double z = (c - n.dot(T.translation())) / n.dot(d);
      ASSERT_NEAR(frame.Depth(u, v), z, 1e-4 * std::max(1.0, z)) << u << "," << v;
      const Eigen::Vector3f normal = frame.gt_normal_world[v * K.width_px + u];
      ASSERT_NEAR(normal.cast<double>().dot(n), 1.0, 1e-5);
    }
  }
}

TEST(DepthCameraTest, OutOfRangeIsInvalid) {
  for (double distance : {0.4, 4.5}) {
    const DepthCamera camera(WallScene(distance), NoiseOff());
    const DepthFrame frame = camera.Render(LookAlongX(), nullptr);
    EXPECT_EQ(frame.NumValid(), 0u) << distance;
    EXPECT_EQ(std::count(frame.gt_instance.begin(), frame.gt_instance.end(), world::kNoInstance),
              static_cast<long>(frame.gt_instance.size()));
  }
}

// Signed distance of point p to a convex polygon given counter-clockwise (positive inside).
double SignedDistanceInside(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d a = hull[i], b = hull[(i + 1) % hull.size()];
    const Eigen::Vector2d e = (b - a).normalized();
    d = std::min(d, e.x() * (p.y() - a.y()) - e.y() * (p.x() - a.x()));
  }
  return d;
}

std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(),
            [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], points[i - 1]) <= 0) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

TEST(DepthCameraTest, BoxSilhouetteMatchesProjectedBox) {
  world::Scene scene("box");
  world::SceneObject box;
  box.instance_id = kBoxId;
  box.category = world::Category::kCabinet;
  const Eigen::Vector3d size(0.6, 0.4, 0.5);
  box.mesh = geometry::MakeBox(size);
  box.T_world_object = geometry::PoseFromXyzRpy(0.3, 0.2, 0.25, 0.0, 0.0, geometry::DegToRad(30));
  scene.Add(box);
  world::SceneObject floor;
  floor.instance_id = kFloorId;
  floor.category = world::Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(-10, -10, 10, 10);
  scene.Add(floor);

  geometry::Pose3 T_world_camera;
  ASSERT_TRUE(geometry::CameraPoseLookAt(Eigen::Vector3d(-1.6, -1.0, 1.2), Eigen::Vector3d(0.3, 0.2, 0.25),
                                         &T_world_camera));
  const DepthCamera camera(scene, NoiseOff());
  const DepthFrame frame = camera.Render(T_world_camera, nullptr);
  const CameraIntrinsics& K = frame.intrinsics;

  std::vector<Eigen::Vector2d> corners;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c_object(((i & 1) ? 0.5 : -0.5) * size.x(), ((i & 2) ? 0.5 : -0.5) * size.y(),
                                   ((i & 4) ? 0.5 : -0.5) * size.z());
    const Eigen::Vector3d c_camera = T_world_camera.inverse() * (box.T_world_object * c_object);
    double u, v;
    ASSERT_TRUE(K.Project(c_camera, &u, &v));
    corners.emplace_back(u, v);
  }
  const std::vector<Eigen::Vector2d> hull = ConvexHull(corners);
  // Image coordinates (x right, y down) flip the orientation: make the hull counter-clockwise in (u, v).
  std::vector<Eigen::Vector2d> ccw = hull;
  double area = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    area += hull[i].x() * hull[(i + 1) % hull.size()].y() - hull[(i + 1) % hull.size()].x() * hull[i].y();
  }
  if (area < 0) std::reverse(ccw.begin(), ccw.end());

  int inside = 0, mismatches = 0;
  for (int v = 0; v < K.height_px; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      const double s = SignedDistanceInside(ccw, Eigen::Vector2d(u, v));
      if (std::abs(s) < 0.01) continue;  // pixel centre on the silhouette edge: either answer is right
      const bool is_box = frame.gt_instance[v * K.width_px + u] == kBoxId;
      inside += s > 0 ? 1 : 0;
      mismatches += (s > 0) != is_box ? 1 : 0;
    }
  }
  EXPECT_GT(inside, 5000);  // the box covers a good part of the image
  EXPECT_EQ(mismatches, 0);
}

// Standard deviation of the valid depths of a frame and the share of valid pixels.
void DepthStats(const DepthFrame& frame, double* mean, double* stddev, double* valid_fraction) {
  double sum = 0.0, sum_sq = 0.0;
  std::size_t n = 0;
  for (float d : frame.depth_m) {
    if (d <= 0.f) continue;
    sum += d;
    sum_sq += static_cast<double>(d) * d;
    ++n;
  }
  *mean = sum / n;
  *stddev = std::sqrt(std::max(0.0, sum_sq / n - *mean * *mean));
  *valid_fraction = static_cast<double>(n) / frame.depth_m.size();
}

TEST(DepthCameraTest, NoiseStddevOnAPlaneMatchesNguyenSigma) {
  const SensorOptions options;  // noise on by default
  ASSERT_TRUE(options.noise);
  const DepthNoiseModel model(options);
  for (double distance : {1.0, 2.0, 3.0}) {
    const DepthCamera camera(WallScene(distance), options);
    Rng rng(11);
    const DepthFrame frame = camera.Render(LookAlongX(), &rng);
    double mean, stddev, valid;
    DepthStats(frame, &mean, &stddev, &valid);
    const double sigma = 0.0012 + 0.0019 * (distance - 0.4) * (distance - 0.4);
    EXPECT_DOUBLE_EQ(model.AxialSigma(distance), sigma);
    EXPECT_NEAR(stddev, sigma, 0.10 * sigma) << "at " << distance << " m";
    EXPECT_NEAR(mean, distance, 0.05 * sigma) << "noise must be unbiased";
    EXPECT_GT(valid, 0.99);  // fronto-parallel plane: no grazing or edge dropouts
  }
}

TEST(DepthCameraTest, DisparityQuantisationAloneGivesDiscreteLevels) {
  SensorOptions options;
  options.noise_sigma_base_m = 0.0;
  options.noise_sigma_quadratic_per_m = 0.0;
  const DepthNoiseModel model(options);
  const double distance = 3.0;
  const DepthCamera camera(WallScene(distance), options);
  Rng rng(3);
  const DepthFrame frame = camera.Render(LookAlongX(), &rng);
  const double fb = options.fx_px * options.baseline_m;
  for (std::size_t i = 0; i < frame.depth_m.size(); i += 97) {
    ASSERT_GT(frame.depth_m[i], 0.f);
    // Disparity on the pixel's grid: fb / z = (k + phase) * step for an integer k.
    const double k = fb / frame.depth_m[i] / options.disparity_step_px - DepthNoiseModel::PixelPhase(i);
    ASSERT_NEAR(k, std::round(k), 1e-4) << i;
  }
  double mean, stddev, valid;
  DepthStats(frame, &mean, &stddev, &valid);
  const double q = model.QuantisationStep(distance);
  EXPECT_NEAR(q, distance * distance * 0.125 / fb, 1e-12);
  EXPECT_NEAR(stddev, q / std::sqrt(12.0), 0.05 * q / std::sqrt(12.0));
}

TEST(DepthCameraTest, GrazingAnglesDropOut) {
  world::Scene scene("floor");
  world::SceneObject floor;
  floor.instance_id = kFloorId;
  floor.category = world::Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(-100, -100, 100, 100);
  scene.Add(floor);
  SensorOptions options;
  options.max_range_m = 50.0;
  options.noise_sigma_base_m = 0.0;  // only the dropouts matter here
  options.noise_sigma_quadratic_per_m = 0.0;
  options.disparity_step_px = 0.0;
  const DepthCamera camera(scene, options);
  const geometry::Pose3 T = geometry::CameraPoseFromYawPitch(Eigen::Vector3d(0, 0, 1.0), 0.0, geometry::DegToRad(-20));
  Rng rng(1);
  const DepthFrame frame = camera.Render(T, &rng);
  const CameraIntrinsics& K = frame.intrinsics;
  int grazing = 0, steep = 0;
  for (int v = 0; v < K.height_px; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      const Eigen::Vector3d d = T.linear() * K.RayCamera(u, v);
      if (d.z() >= 0) continue;
      const double incidence_deg = geometry::RadToDeg(std::acos(-d.z() / d.norm()));
      const bool valid = frame.Depth(u, v) > 0.f;
      if (incidence_deg > 75.5) {
        ++grazing;
        ASSERT_FALSE(valid) << u << "," << v << " at " << incidence_deg << " deg";
      } else if (incidence_deg < 74.5) {
        ++steep;
        ASSERT_TRUE(valid) << u << "," << v << " at " << incidence_deg << " deg";
      }
    }
  }
  EXPECT_GT(grazing, 1000);
  EXPECT_GT(steep, 1000);
}

TEST(DepthCameraTest, DepthDiscontinuitiesDropOut) {
  world::Scene scene = WallScene(3.0);
  world::SceneObject box;
  box.instance_id = kBoxId;
  box.mesh = geometry::MakeBox(Eigen::Vector3d(1.5, -0.3, -0.3), Eigen::Vector3d(1.8, 0.3, 0.3));
  scene.Add(box);
  SensorOptions options;
  options.noise_sigma_base_m = 0.0;
  options.noise_sigma_quadratic_per_m = 0.0;
  options.disparity_step_px = 0.0;
  const DepthCamera noisy(scene, options);
  const DepthCamera ideal(scene, NoiseOff());
  Rng rng(2);
  const DepthFrame with_dropout = noisy.Render(LookAlongX(), &rng);
  const DepthFrame truth = ideal.Render(LookAlongX(), nullptr);
  const int w = truth.width(), h = truth.height();
  int edge_pixels = 0;
  for (int v = 1; v + 1 < h; ++v) {
    for (int u = 1; u + 1 < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      ASSERT_GT(truth.depth_m[i], 0.f);
      const std::int32_t id = truth.gt_instance[i];
      const bool on_edge = truth.gt_instance[i - 1] != id || truth.gt_instance[i + 1] != id ||
                           truth.gt_instance[i - w] != id || truth.gt_instance[i + w] != id;
      edge_pixels += on_edge ? 1 : 0;
      ASSERT_EQ(with_dropout.depth_m[i] > 0.f, !on_edge) << u << "," << v;
    }
  }
  EXPECT_GT(edge_pixels, 400);  // both sides of the box outline
}

bool SameFrame(const DepthFrame& a, const DepthFrame& b) {
  return a.depth_m == b.depth_m && a.gt_instance == b.gt_instance && a.gt_normal_world == b.gt_normal_world;
}

world::Scene ClutteredScene() {
  world::Scene scene = WallScene(3.5);
  world::SceneObject floor;
  floor.category = world::Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(-5, -5, 5, 5);
  floor.T_world_object.translation() = Eigen::Vector3d(0, 0, -1.2);
  scene.Add(floor);
  for (int i = 0; i < 6; ++i) {
    world::SceneObject o;
    o.mesh = i % 2 ? geometry::MakeSphere(0.2 + 0.05 * i) : geometry::MakeCylinder(0.15, 0.8);
    o.T_world_object.translation() = Eigen::Vector3d(1.2 + 0.3 * i, -1.0 + 0.4 * i, -0.8 + 0.2 * i);
    scene.Add(o);
  }
  return scene;
}

TEST(DepthCameraTest, SameSeedSameFrame) {
  const DepthCamera camera(ClutteredScene(), SensorOptions());
  Rng a(42), b(42), c(43);
  const DepthFrame fa = camera.Render(LookAlongX(), &a);
  const DepthFrame fb = camera.Render(LookAlongX(), &b);
  const DepthFrame fc = camera.Render(LookAlongX(), &c);
  EXPECT_TRUE(SameFrame(fa, fb));
  EXPECT_NE(fa.depth_m, fc.depth_m);
  EXPECT_GT(fa.NumValid(), fa.depth_m.size() / 2);
}

TEST(DepthCameraTest, DifferentThreadCountsSameFrame) {
  const world::Scene scene = ClutteredScene();
  std::vector<DepthFrame> frames;
  for (int threads : {1, 2, 3, 8}) {
    SensorOptions options;
    options.threads = threads;
    const DepthCamera camera(scene, options);
    Rng rng(99);
    frames.push_back(camera.Render(LookAlongX(), &rng));
  }
  for (std::size_t k = 1; k < frames.size(); ++k) EXPECT_TRUE(SameFrame(frames[0], frames[k])) << k;
}

TEST(DepthCameraTest, RejectsBadInput) {
  EXPECT_THROW(DepthCamera(world::Scene("empty"), SensorOptions()), InputError);
  SensorOptions bad;
  bad.max_range_m = 0.2;
  EXPECT_THROW(DepthCamera(WallScene(2.0), bad), ConfigError);
  const DepthCamera camera(WallScene(2.0), SensorOptions());
  EXPECT_THROW(camera.Render(LookAlongX(), nullptr), InputError);  // noise on needs an Rng
  geometry::Pose3 nan_pose = LookAlongX();
  nan_pose.translation().x() = std::numeric_limits<double>::quiet_NaN();
  Rng rng(1);
  EXPECT_THROW(camera.Render(nan_pose, &rng), InputError);
}

}  // namespace
}  // namespace objscan::render
