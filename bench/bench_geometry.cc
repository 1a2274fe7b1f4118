// Benchmarks of the core geometry: building the ray caster's triangle soup from a scene.
#include <benchmark/benchmark.h>

#include "objscan/geometry/mesh.h"
#include "objscan/world/scene.h"

namespace {

void BM_BuildTriangleSoup(benchmark::State& state) {
  objscan::world::Scene scene("bench");
  for (int i = 0; i < 200; ++i) {
    objscan::world::SceneObject o;
    o.mesh = objscan::geometry::MakeSphere(0.2, 32);
    o.T_world_object.translation() = Eigen::Vector3d(i % 20, i / 20, 0.5);
    scene.Add(std::move(o));
  }
  for (auto _ : state) benchmark::DoNotOptimize(scene.BuildTriangleSoup());
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(scene.NumTriangles()));
}
BENCHMARK(BM_BuildTriangleSoup)->Unit(benchmark::kMillisecond);

}  // namespace
