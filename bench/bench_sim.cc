// Benchmarks of the simulator: one depth frame of procedural:bedroom:1 through render::DepthCamera
// against the same rays through a plain per-ray rtcIntersect1 loop on an identically built Embree
// scene (the peer), and A* on the room's grid.
//
// Both frame benchmarks run on one thread. BM_RenderDepthFrame includes everything a frame costs
// (ray generation, 16-ray packets, normals, dropouts and noise as configured by default);
// BM_EmbreeRawRays gets its rays precomputed and only stores distance and triangle per ray.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <stdexcept>

#include "objscan/common/rng.h"
#include "objscan/render/depth_camera.h"
#include "objscan/sim/ground_truth_occupancy.h"
#include "objscan/navigation/navigator.h"
#include "objscan/world/procedural/procedural.h"

namespace {

using namespace objscan;

const world::Scene& Bedroom() {
  static const world::Scene scene = world::procedural::GenerateRoom("bedroom", 1);
  return scene;
}

// From the door side of the room looking at the bed, both night stands and the shelves.
geometry::Pose3 BenchCameraPose() {
  return geometry::CameraPoseFromYawPitch(Eigen::Vector3d(2.0, 1.0, 1.4), geometry::DegToRad(90),
                                          geometry::DegToRad(-25));
}

void BM_RenderDepthFrame(benchmark::State& state) {
  render::SensorOptions options;  // 640x480, noise on (the default)
  options.noise = state.range(0) != 0;
  options.threads = 1;
  const render::DepthCamera camera(Bedroom(), options);
  const geometry::Pose3 pose = BenchCameraPose();
  Rng rng(1);
  std::size_t valid = 0;
  for (auto _ : state) {
    const platform::DepthFrame frame = camera.Render(pose, &rng);
    valid = frame.NumValid();
    benchmark::DoNotOptimize(frame.depth_m.data());
  }
  state.counters["valid_pixels"] = static_cast<double>(valid);
  state.SetItemsProcessed(state.iterations() * options.width_px * options.height_px);
}
BENCHMARK(BM_RenderDepthFrame)->Arg(1)->ArgName("noise")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderDepthFrame)->Arg(0)->ArgName("noise")->Unit(benchmark::kMillisecond);

// The peer: the scene committed exactly as render::Raycaster does (one triangle geometry, robust flag,
// high build quality), the frame's rays one by one through rtcIntersect1.
void BM_EmbreeRawRays(benchmark::State& state) {
  const world::TriangleSoup soup = Bedroom().BuildTriangleSoup();
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), soup.vertices_xyz.size() / 3));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), soup.NumTriangles()));
  std::copy(soup.vertices_xyz.begin(), soup.vertices_xyz.end(), vertices);
  std::copy(soup.triangles.begin(), soup.triangles.end(), indices);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw std::runtime_error("embree error in BM_EmbreeRawRays");

  // The same rays as the depth camera: pixel centres, camera-frame z = 1, in row-major order.
  const platform::CameraIntrinsics K = render::SensorOptions().Intrinsics();
  const geometry::Pose3 pose = BenchCameraPose();
  std::vector<float> directions;
  directions.reserve(3 * static_cast<std::size_t>(K.NumPixels()));
  for (int v = 0; v < K.height_px; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      const Eigen::Vector3d d = pose.linear() * K.RayCamera(u, v);
      directions.insert(directions.end(), {float(d.x()), float(d.y()), float(d.z())});
    }
  }
  const Eigen::Vector3f origin = pose.translation().cast<float>();
  std::vector<float> distance(K.NumPixels());
  std::vector<unsigned> triangle(K.NumPixels());
  std::size_t hits = 0;
  for (auto _ : state) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    hits = 0;
    for (int i = 0; i < K.NumPixels(); ++i) {
      RTCRayHit rh;
      rh.ray.org_x = origin.x();
      rh.ray.org_y = origin.y();
      rh.ray.org_z = origin.z();
      rh.ray.dir_x = directions[3 * i];
      rh.ray.dir_y = directions[3 * i + 1];
      rh.ray.dir_z = directions[3 * i + 2];
      rh.ray.tnear = 0.f;
      rh.ray.tfar = std::numeric_limits<float>::infinity();
      rh.ray.time = 0.f;
      rh.ray.mask = ~0u;
      rh.ray.id = 0;
      rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &context, &rh);
      const bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      distance[i] = hit ? rh.ray.tfar : 0.f;
      triangle[i] = rh.hit.primID;
      hits += hit ? 1 : 0;
    }
    benchmark::DoNotOptimize(distance.data());
    benchmark::DoNotOptimize(triangle.data());
  }
  state.counters["hits"] = static_cast<double>(hits);
  state.SetItemsProcessed(state.iterations() * K.NumPixels());
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
}
BENCHMARK(BM_EmbreeRawRays)->Unit(benchmark::kMillisecond);

// A* across the bedroom's 5 cm grid (robot radius 0.25 m, 1.8 m tall): from the gap right of the bed
// around its foot into the gap left of it.
void BM_AStar(benchmark::State& state) {
  const sim::GroundTruthOccupancy source(Bedroom());
  navigation::NavigatorOptions options;
  options.smooth_path = state.range(0) != 0;
  const navigation::Navigator nav(source, 0.25, 1.8, options);
  Eigen::Vector2d start, goal;
  if (!nav.NearestFree(Eigen::Vector2d(3.2, 3.2), 0.5, &start) || !nav.NearestFree(Eigen::Vector2d(0.45, 3.0), 0.5, &goal)) {
    state.SkipWithError("no free start or goal in the bedroom");
    return;
  }
  double length = 0.0;
  int expansions = 0;
  for (auto _ : state) {
    const navigation::Path2D path = nav.Plan(start, goal);
    length = path.length_m;
    expansions = path.expansions;
    benchmark::DoNotOptimize(path.waypoints.data());
  }
  state.counters["length_m"] = length;
  state.counters["expansions"] = expansions;
  state.counters["cells"] = static_cast<double>(nav.grid().NumCells());
}
BENCHMARK(BM_AStar)->Arg(1)->ArgName("smooth")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AStar)->Arg(0)->ArgName("smooth")->Unit(benchmark::kMicrosecond);

void BM_GroundTruthOccupancyGrid(benchmark::State& state) {
  const sim::GroundTruthOccupancy source(Bedroom());
  for (auto _ : state) benchmark::DoNotOptimize(source.Grid(0.02, 1.8, 0.05).cells.data());
}
BENCHMARK(BM_GroundTruthOccupancyGrid)->Unit(benchmark::kMillisecond);

}  // namespace
