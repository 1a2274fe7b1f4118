// Mapping and pre-segmentation on one frame of procedural:bedroom:1, with Open3D's scalable TSDF
// integration of the same frame at the same voxel size as the peer (built when Open3D is found).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "objscan/geometry/pose.h"
#include "objscan/mapping/occupancy_map.h"
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
