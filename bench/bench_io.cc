// Benchmarks of scene I/O: loading an OASC world, drawing a top view, PLY writing and reading
// (with Open3D's PLY point-cloud I/O as the peer when it is available).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "objscan/io/ply.h"
#include "objscan/io/scene_spec.h"
#include "objscan/io/topview.h"

#ifdef OBJSCAN_HAVE_OPEN3D
#include <open3d/geometry/PointCloud.h>
#include <open3d/io/PointCloudIO.h>
#endif

namespace {

namespace fs = std::filesystem;

// ../shared/data next to the project root or the working directory.
std::string SharedData() {
  for (const char* candidate : {"../shared/data", "../../shared/data", "../../../shared/data"}) {
    if (fs::is_directory(candidate)) return candidate;
  }
  return "";
}

void BM_LoadOascWorld(benchmark::State& state) {
  const std::string data = SharedData();
  if (data.empty()) {
    state.SkipWithError("../shared/data not found");
    return;
  }
  objscan::io::SceneLoadOptions options;
  options.model_path = data + "/gazebo-models";
  const std::string world = data + "/oasc-dev/SUNCG/living_room/20bb3f81a2161f2f3d533afe221767cf/0_5/room.world";
  std::size_t triangles = 0;
  for (auto _ : state) {
    const objscan::world::Scene scene = objscan::io::LoadScene(world, options);
    triangles = scene.NumTriangles();
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_LoadOascWorld)->Unit(benchmark::kMillisecond);

void BM_RenderTopView(benchmark::State& state) {
  const objscan::world::Scene scene = objscan::io::LoadScene("procedural:living_room:1", {});
  objscan::io::TopViewOptions options;
  for (auto _ : state) benchmark::DoNotOptimize(objscan::io::RenderTopView(scene, options).canvas.width());
  state.counters["triangles"] = static_cast<double>(scene.NumTriangles());
}
BENCHMARK(BM_RenderTopView)->Unit(benchmark::kMillisecond);

objscan::io::PlyData Cloud(int n) {
  objscan::io::PlyData d;
  for (int i = 0; i < n; ++i) {
    d.points.emplace_back(0.001f * i, 0.5f * (i % 7), 0.25f * (i % 13));
    d.normals.emplace_back(0, 0, 1);
  }
  return d;
}

std::string TempFile(const char* name) { return (fs::temp_directory_path() / name).string(); }

void BM_PlyWriteBinary(benchmark::State& state) {
  const auto d = Cloud(static_cast<int>(state.range(0)));
  const std::string path = TempFile("objscan_bench_binary.ply");
  for (auto _ : state) objscan::io::WritePly(path, d, true);
  state.SetItemsProcessed(state.iterations() * state.range(0));
  std::remove(path.c_str());
}
BENCHMARK(BM_PlyWriteBinary)->Arg(1 << 20)->Unit(benchmark::kMillisecond);

void BM_PlyReadBinary(benchmark::State& state) {
  const std::string path = TempFile("objscan_bench_read.ply");
  objscan::io::WritePly(path, Cloud(static_cast<int>(state.range(0))), true);
  for (auto _ : state) benchmark::DoNotOptimize(objscan::io::ReadPly(path).points.size());
  state.SetItemsProcessed(state.iterations() * state.range(0));
  std::remove(path.c_str());
}
BENCHMARK(BM_PlyReadBinary)->Arg(1 << 20)->Unit(benchmark::kMillisecond);

#ifdef OBJSCAN_HAVE_OPEN3D
open3d::geometry::PointCloud Open3dCloud(int n) {
  const auto d = Cloud(n);
  open3d::geometry::PointCloud pc;
  for (int i = 0; i < n; ++i) {
    pc.points_.push_back(d.points[i].cast<double>());
    pc.normals_.push_back(d.normals[i].cast<double>());
  }
  return pc;
}

void BM_Open3dPlyWriteBinary(benchmark::State& state) {
  const auto pc = Open3dCloud(static_cast<int>(state.range(0)));
  const std::string path = TempFile("objscan_bench_open3d.ply");
  for (auto _ : state) open3d::io::WritePointCloud(path, pc);
  state.SetItemsProcessed(state.iterations() * state.range(0));
  std::remove(path.c_str());
}
BENCHMARK(BM_Open3dPlyWriteBinary)->Arg(1 << 20)->Unit(benchmark::kMillisecond);

void BM_Open3dPlyReadBinary(benchmark::State& state) {
  const std::string path = TempFile("objscan_bench_open3d_read.ply");
  objscan::io::WritePly(path, Cloud(static_cast<int>(state.range(0))), true);
  for (auto _ : state) {
    open3d::geometry::PointCloud pc;
    open3d::io::ReadPointCloud(path, pc);
    benchmark::DoNotOptimize(pc.points_.size());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  std::remove(path.c_str());
}
BENCHMARK(BM_Open3dPlyReadBinary)->Arg(1 << 20)->Unit(benchmark::kMillisecond);
#endif

}  // namespace
