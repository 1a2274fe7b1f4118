#include "objscan/recognition/virtual_scan.h"

#include <algorithm>
#include <cmath>

#include "objscan/common/error.h"
#include "objscan/world/scene.h"

namespace objscan::recognition {

void VirtualScanOptions::Validate() const {
  config::Require(!ring_elevations_deg.empty(), "recognition.scan.ring_elevations_deg", "needs at least one ring");
  config::Require(ring_views.size() == ring_elevations_deg.size(), "recognition.scan.ring_views",
                  "needs one count per ring elevation");
  for (double e : ring_elevations_deg)
    config::RequireInRange("recognition.scan.ring_elevations_deg", e, -30.0, 89.0);
  for (double n : ring_views)
    config::Require(n >= 1.0 && n == std::floor(n), "recognition.scan.ring_views", "must be whole numbers >= 1");
  config::RequirePositive("recognition.scan.distance_per_diagonal", distance_per_diagonal);
  config::RequireNonNegative("recognition.scan.distance_margin_m", distance_margin_m);
  sensor.Validate();
  map.Validate();
  segmenter.Validate();
}

double ViewDistance(const geometry::Aabb3& bounds, const VirtualScanOptions& options) {
  const double diag = bounds.Diagonal();
  const double wanted = options.distance_per_diagonal * diag + options.distance_margin_m;
  // Keep the whole model within the valid depth range where possible.
  const double lo = options.sensor.min_range_m + 0.5 * diag + 0.1;
  const double hi = std::max(lo, options.sensor.max_range_m - 0.5 * diag - 0.05);
  return std::clamp(wanted, lo, hi);
}

geometry::Pose3 ViewFrom(const geometry::Aabb3& bounds, double azimuth_rad, double elevation_rad,
                         const VirtualScanOptions& options) {
  const Eigen::Vector3d centre = bounds.Center();
  const double d = ViewDistance(bounds, options);
  const Eigen::Vector3d position =
      centre + d * Eigen::Vector3d(std::cos(elevation_rad) * std::cos(azimuth_rad),
                                   std::cos(elevation_rad) * std::sin(azimuth_rad), std::sin(elevation_rad));
  geometry::Pose3 T_world_camera = geometry::Pose3::Identity();
  geometry::CameraPoseLookAt(position, centre, &T_world_camera);
  return T_world_camera;
}

std::vector<geometry::Pose3> RingViews(const geometry::Aabb3& bounds, const VirtualScanOptions& options) {
  std::vector<geometry::Pose3> views;
  for (std::size_t r = 0; r < options.ring_elevations_deg.size(); ++r) {
    const int n = static_cast<int>(options.ring_views[r]);
    // Alternate rings are offset by half a step so elevated views fill the gaps of the lower ring.
    const double offset = (r % 2 == 1) ? M_PI / n : 0.0;
    for (int k = 0; k < n; ++k) {
      views.push_back(ViewFrom(bounds, offset + 2.0 * M_PI * k / n,
                               geometry::DegToRad(options.ring_elevations_deg[r]), options));
    }
  }
  return views;
}

namespace {

// The scene a model is scanned in: the mesh alone.
world::Scene ModelAlone(const geometry::TriangleMesh& mesh) {
  world::Scene scene("virtual-scan");
  world::SceneObject object;
  object.category = world::Category::kOther;
  object.name = "model";
  object.mesh = mesh;
  scene.Add(std::move(object));
  return scene;
}

}  // namespace

ModelScan ScanModel(const geometry::TriangleMesh& mesh, const std::vector<geometry::Pose3>& views,
                    const VirtualScanOptions& options, bool noise, Rng* rng) {
  const world::Scene scene = ModelAlone(mesh);
  render::SensorOptions sensor = options.sensor;
  sensor.noise = noise;
  const render::DepthCamera camera(scene, sensor);
  mapping::SurfaceMap map(options.map);
  segmentation::IncrementalSegmenter segmenter(options.segmenter);
  mapping::FrameAssociation association;
  for (const auto& T_world_camera : views) {
    const platform::DepthFrame frame = camera.Render(T_world_camera, noise ? rng : nullptr);
    map.Integrate(frame, &association);
    segmenter.Update(frame, association, &map);
  }
  ModelScan scan;
  scan.components = segmenter.Components(&map);
  scan.surface = map.AllPoints();
  return scan;
}

geometry::PointCloud ScanSurface(const geometry::TriangleMesh& mesh, const std::vector<geometry::Pose3>& views,
                                 const VirtualScanOptions& options, bool noise, Rng* rng) {
  const world::Scene scene = ModelAlone(mesh);
  render::SensorOptions sensor = options.sensor;
  sensor.noise = noise;
  const render::DepthCamera camera(scene, sensor);
  mapping::SurfaceMap map(options.map);
  mapping::FrameAssociation association;
  for (const auto& T_world_camera : views) map.Integrate(camera.Render(T_world_camera, noise ? rng : nullptr), &association);
  return map.AllPoints();
}

geometry::PointCloud HalfOf(const geometry::PointCloud& cloud, Rng* rng) {
  if (cloud.points.empty()) return cloud;
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  for (const auto& p : cloud.points) centroid += p;
  centroid /= static_cast<float>(cloud.points.size());
  const double angle = rng->Uniform(-M_PI, M_PI);
  const Eigen::Vector3f side(static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle)), 0.f);
  geometry::PointCloud half;
  const bool with_normals = cloud.normals.size() == cloud.points.size();
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if ((cloud.points[i] - centroid).dot(side) < 0.f) continue;
    half.points.push_back(cloud.points[i]);
    if (with_normals) half.normals.push_back(cloud.normals[i]);
  }
  return half;
}

double TypicalHeight(world::Category category) {
  using world::Category;
  switch (category) {
    case Category::kBathtub: return 0.6;
    case Category::kBed: return 0.9;
    case Category::kCabinet: return 1.2;
    case Category::kCan: return 0.3;
    case Category::kChair: return 0.9;
    case Category::kCurtain: return 2.2;
    case Category::kDesk: return 0.75;
    case Category::kDoor: return 2.0;
    case Category::kDresser: return 0.9;
    case Category::kLamp: return 0.6;
    case Category::kMonitor: return 0.45;
    case Category::kNightStand: return 0.55;
    case Category::kRadio: return 0.2;
    case Category::kRefrigerator: return 1.8;
    case Category::kShelves: return 1.8;
    case Category::kSink: return 0.9;
    case Category::kSofa: return 0.85;
    case Category::kTable: return 0.75;
    case Category::kToilet: return 0.8;
    case Category::kTvStand: return 0.5;
    case Category::kWindow: return 1.2;
    default: return 1.0;
  }
}

geometry::TriangleMesh NormalizeModel(const geometry::TriangleMesh& mesh, double typical_height_m) {
  const geometry::Aabb3 box = geometry::Bounds(mesh);
  if (box.Empty()) return mesh;
  double scale = 1.0;
  const double diag = box.Diagonal();
  if ((diag > 20.0 || diag < 0.05) && box.Size().z() > 0.0) scale = typical_height_m / box.Size().z();
  const Eigen::Vector3d c = box.Center();
  const Eigen::Affine3d T = Eigen::Translation3d(-scale * c.x(), -scale * c.y(), -scale * box.min_m.z()) * Eigen::Scaling(scale);
  return geometry::Transformed(mesh, T);
}

}  // namespace objscan::recognition
