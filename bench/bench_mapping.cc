// Mapping and pre-segmentation on one frame of procedural:bedroom:1, with Open3D's scalable TSDF
// integration of the same frame at the same voxel size as the peer (built when Open3D is found).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "objscan/geometry/pose.h"
#include "objscan/mapping/occupancy_map.h"
#include "objscan/mapping/planes.h"
#include "objscan/mapping/surface_map.h"
#include "objscan/segmentation/incremental_segmenter.h"
#include "objscan/render/depth_camera.h"
#include "objscan/world/procedural/procedural.h"

#ifdef OBJSCAN_HAVE_OPEN3D
#include <open3d/Open3D.h>
#endif

namespace {

using namespace objscan;

// One noisy frame from the middle of the room looking across it, rendered once.
const platform::DepthFrame& BedroomFrame() {
  static const platform::DepthFrame frame = [] {
    const world::Scene scene = world::procedural::GenerateRoom("bedroom", 1);
    render::SensorOptions sensor;
    sensor.threads = 1;
    const render::DepthCamera camera(scene, sensor);
    const geometry::Aabb3 box = scene.Bounds();
    Eigen::Vector3d eye = box.Center();
    eye.z() = 1.3;
    Rng rng(1);
    return camera.Render(geometry::CameraPoseFromYawPitch(eye, 0.6, geometry::DegToRad(-25.0)), &rng);
  }();
  return frame;
}

void BM_FuseFrame(benchmark::State& state) {
  const platform::DepthFrame& frame = BedroomFrame();
  for (auto _ : state) {
    state.PauseTiming();
    auto map = std::make_unique<mapping::SurfaceMap>();
    state.ResumeTiming();
    map->Integrate(frame);
    benchmark::DoNotOptimize(map->size());
  }
  state.counters["valid_px"] = static_cast<double>(frame.NumValid());
}
BENCHMARK(BM_FuseFrame)->Unit(benchmark::kMillisecond);

// Fusing into a map that already holds the surface (the steady state of a scan).
void BM_FuseFrameRevisit(benchmark::State& state) {
  const platform::DepthFrame& frame = BedroomFrame();
  mapping::SurfaceMap map;
  map.Integrate(frame);
  for (auto _ : state) {
    map.Integrate(frame);
    benchmark::DoNotOptimize(map.size());
  }
}
BENCHMARK(BM_FuseFrameRevisit)->Unit(benchmark::kMillisecond);

void BM_OctomapInsert(benchmark::State& state) {
  const platform::DepthFrame& frame = BedroomFrame();
  for (auto _ : state) {
    state.PauseTiming();
    auto occupancy = std::make_unique<mapping::OccupancyMap>();
    state.ResumeTiming();
    occupancy->Integrate(frame);
    benchmark::DoNotOptimize(occupancy.get());
  }
}
BENCHMARK(BM_OctomapInsert)->Unit(benchmark::kMillisecond);

// Frame segmentation + propagation + voting (fusion excluded: its association is an input).
void BM_PresegmentFrame(benchmark::State& state) {
  const platform::DepthFrame& frame = BedroomFrame();
  mapping::SurfaceMap map;
  mapping::FrameAssociation association;
  map.Integrate(frame, &association);
  segmentation::IncrementalSegmenter segmenter;
  for (auto _ : state) {
    benchmark::DoNotOptimize(segmenter.Update(frame, association, &map));
  }
}
BENCHMARK(BM_PresegmentFrame)->Unit(benchmark::kMillisecond);

// The structure-residue tests the scanner runs on every component each step, on a 5 m x 4 m room
// (floor and four walls) and a component of N points spread over furniture in its middle (the common
// case: no plane holds it, so every plane is tried): the plane-noise test against its peer, the
// per-point OnStructure test that runs beside it.
mapping::StructureResult FourWallRoom() {
  mapping::StructureResult s;
  s.has_floor = true;
  const double kHalfX = 2.5, kHalfY = 2.0;
  const Eigen::Vector2d normals[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  const double offsets[4] = {-kHalfX, -kHalfX, -kHalfY, -kHalfY};
  for (int k = 0; k < 4; ++k) {
    mapping::WallPlane w;
    w.normal = Eigen::Vector3d(normals[k].x(), normals[k].y(), 0.0);
    w.offset_m = offsets[k];
    w.z_max_m = 2.5;
    w.span_min_m = -3.0;
    w.span_max_m = 3.0;
    s.walls.push_back(w);
  }
  return s;
}
void FurniturePoints(int n, std::vector<Eigen::Vector3f>* points, std::vector<Eigen::Vector3f>* normals) {
  for (int i = 0; i < n; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(n);
    points->emplace_back(-0.5f + t, 0.3f * std::sin(40.0f * t), 0.1f + 0.8f * t);
    normals->emplace_back(0.0f, 0.0f, 1.0f);
  }
}
void BM_PlaneNoiseTest(benchmark::State& state) {
  const mapping::StructureResult room = FourWallRoom();
  std::vector<Eigen::Vector3f> points, normals;
  FurniturePoints(static_cast<int>(state.range(0)), &points, &normals);
  for (auto _ : state) benchmark::DoNotOptimize(room.IsPlaneNoise(points, normals, 0.08, 0.2, 0.8));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_PlaneNoiseTest)->Arg(20000)->Unit(benchmark::kMicrosecond);
void BM_OnStructurePerPoint(benchmark::State& state) {
  const mapping::StructureResult room = FourWallRoom();
  std::vector<Eigen::Vector3f> points, normals;
  FurniturePoints(static_cast<int>(state.range(0)), &points, &normals);
  for (auto _ : state) {
    std::size_t near = 0;
    for (const auto& p : points) near += room.OnStructure(p.cast<double>(), 0.04);
    benchmark::DoNotOptimize(near);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_OnStructurePerPoint)->Arg(20000)->Unit(benchmark::kMicrosecond);

#ifdef OBJSCAN_HAVE_OPEN3D
// The bedroom frame as Open3D's input: an RGBD image (depth in metres, no colour), its intrinsics and
// the extrinsic (world -> camera), fused at objscan's voxel size with a 4-voxel truncation.
struct Open3dFrame {
  std::shared_ptr<open3d::geometry::RGBDImage> rgbd;
  open3d::camera::PinholeCameraIntrinsic intrinsic;
  Eigen::Matrix4d extrinsic;
  double voxel_m;
};

Open3dFrame MakeOpen3dFrame() {
  const platform::DepthFrame& frame = BedroomFrame();
  const platform::CameraIntrinsics& in = frame.intrinsics;
  open3d::geometry::Image depth;
  depth.Prepare(in.width_px, in.height_px, 1, 4);
  std::memcpy(depth.data_.data(), frame.depth_m.data(), frame.depth_m.size() * sizeof(float));
  open3d::geometry::Image color;
  color.Prepare(in.width_px, in.height_px, 3, 1);
  Open3dFrame f;
  f.rgbd = open3d::geometry::RGBDImage::CreateFromColorAndDepth(color, depth, /*depth_scale=*/1.0,
                                                                /*depth_trunc=*/in.max_range_m,
                                                                /*convert_rgb_to_intensity=*/false);
  f.intrinsic = open3d::camera::PinholeCameraIntrinsic(in.width_px, in.height_px, in.fx_px, in.fy_px, in.cx_px, in.cy_px);
  f.extrinsic = frame.T_world_camera.inverse().matrix();
  f.voxel_m = mapping::SurfaceMapOptions().voxel_size_m;
  return f;
}

std::unique_ptr<open3d::pipelines::integration::ScalableTSDFVolume> MakeOpen3dVolume(double voxel_m) {
  return std::make_unique<open3d::pipelines::integration::ScalableTSDFVolume>(
      voxel_m, /*sdf_trunc=*/4.0 * voxel_m, open3d::pipelines::integration::TSDFVolumeColorType::NoColor);
}

void BM_Open3DTsdfIntegrate(benchmark::State& state) {
  const Open3dFrame f = MakeOpen3dFrame();
  for (auto _ : state) {
    state.PauseTiming();
    auto volume = MakeOpen3dVolume(f.voxel_m);
    state.ResumeTiming();
    volume->Integrate(*f.rgbd, f.intrinsic, f.extrinsic);
    benchmark::DoNotOptimize(volume.get());
  }
}
BENCHMARK(BM_Open3DTsdfIntegrate)->Unit(benchmark::kMillisecond);

// The same frame into a volume that already holds it: the peer of BM_FuseFrameRevisit.
void BM_Open3DTsdfIntegrateRevisit(benchmark::State& state) {
  const Open3dFrame f = MakeOpen3dFrame();
  auto volume = MakeOpen3dVolume(f.voxel_m);
  volume->Integrate(*f.rgbd, f.intrinsic, f.extrinsic);
  for (auto _ : state) {
    volume->Integrate(*f.rgbd, f.intrinsic, f.extrinsic);
    benchmark::DoNotOptimize(volume.get());
  }
}
BENCHMARK(BM_Open3DTsdfIntegrateRevisit)->Unit(benchmark::kMillisecond);
#endif

}  // namespace
