// Benchmarks of the planning stage: next best view (16 candidates x 5 aligned models around a ~1 m
// object, 2.5 cm voxels) and next best object (50 objects).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "objscan/common/rng.h"
#include "objscan/planning/next_best_object.h"
#include "objscan/planning/next_best_view.h"

namespace {

using Points = std::vector<Eigen::Vector3f>;

void AddBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double spacing_m, Points* out) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int nu = static_cast<int>(std::ceil((hi[u] - lo[u]) / spacing_m));
    const int nv = static_cast<int>(std::ceil((hi[v] - lo[v]) / spacing_m));
    for (double side : {lo[axis], hi[axis]}) {
      for (int i = 0; i <= nu; ++i) {
        for (int j = 0; j <= nv; ++j) {
          Eigen::Vector3d p;
          p[axis] = side;
          p[u] = std::min(hi[u], lo[u] + i * spacing_m);
          p[v] = std::min(hi[v], lo[v] + j * spacing_m);
          out->push_back(p.cast<float>());
        }
      }
    }
  }
}

// A 1.0 x 0.8 x 0.75 m table: top plus four legs; `variant` moves the legs, thickens the top or adds a
// shelf, so the five candidate models disagree in places.
Points Table(int variant) {
  Points pts;
  const double top_thickness = variant == 2 ? 0.08 : 0.04;
  AddBox({-0.5, -0.4, 0.75 - top_thickness}, {0.5, 0.4, 0.75}, 0.01, &pts);
  const double inset = variant == 1 ? 0.15 : 0.03;
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      const double cx = sx * (0.5 - inset - 0.025), cy = sy * (0.4 - inset - 0.025);
      AddBox({cx - 0.025, cy - 0.025, 0.0}, {cx + 0.025, cy + 0.025, 0.75 - top_thickness}, 0.01, &pts);
    }
  }
  if (variant == 3) AddBox({-0.45, -0.35, 0.25}, {0.45, 0.35, 0.27}, 0.01, &pts);  // shelf
  if (variant == 4) AddBox({0.3, -0.4, 0.45}, {0.5, 0.4, 0.71}, 0.01, &pts);       // drawer block on +X
  return pts;
}

void BM_NextBestView(benchmark::State& state) {
  std::vector<Points> models;
  for (int v = 0; v < 5; ++v) models.push_back(Table(v));
  Points gamma;  // observed from -X: the -X half of the plain table
  for (const Eigen::Vector3f& p : models[0]) {
    if (p.x() < 0.0f) gamma.push_back(p);
  }
  objscan::planning::NextBestViewInput input;
  input.gamma_points_world = &gamma;
  const double objectness[5] = {0.6, 0.5, 0.45, 0.4, 0.3};
  for (int v = 0; v < 5; ++v) input.models.push_back({v, objectness[v], &models[v]});
  Points floor;  // map surface under the table: it cannot hide anything above it but slows the walks
  for (double x = -0.8; x <= 0.8; x += 0.01) {
    for (double y = -0.7; y <= 0.7; y += 0.01) floor.emplace_back(x, y, -0.005);
  }
  if (state.range(2) != 0) input.occluder_points_world = &floor;
  objscan::planning::NextBestViewOptions options;
  options.voxel_size_m = state.range(0) / 1000.0;
  options.threads = static_cast<int>(state.range(1));
  objscan::planning::NextBestView nbv(options);
  int delta_voxels = 0;
  for (auto _ : state) {
    const objscan::planning::NextBestViewResult r = nbv.Plan(input, nullptr);
    delta_voxels = r.delta_voxels;
    benchmark::DoNotOptimize(r.best_index);
  }
  state.counters["delta_voxels"] = delta_voxels;
  state.counters["candidates"] = options.candidates.num_candidates;
}
// Arguments: voxel size in mm, threads, floor occluder on/off.
BENCHMARK(BM_NextBestView)
    ->Args({20, 1, 1})
    ->Args({25, 1, 1})
    ->Args({30, 1, 1})
    ->Args({25, 2, 1})
    ->Args({25, 1, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A coverage view (scanning/coverage_views.h): the same table seen from -X, its one model, the
// unseen model surface counted instead of the information gain; against BM_NextBestView/25/1/1.
void BM_CoverageView(benchmark::State& state) {
  const Points model = Table(0);
  Points gamma;
  for (const Eigen::Vector3f& p : model) {
    if (p.x() < 0.0f) gamma.push_back(p);
  }
  Points floor;
  for (double x = -0.8; x <= 0.8; x += 0.01) {
    for (double y = -0.7; y <= 0.7; y += 0.01) floor.emplace_back(x, y, -0.005);
  }
  objscan::planning::NextBestViewInput input;
  input.gamma_points_world = &gamma;
  input.models = {{0, 1.0, &model}};
  input.occluder_points_world = &floor;
  input.gain_measure = objscan::planning::ViewGainMeasure::kUnobservedSurface;
  objscan::planning::NextBestViewOptions options;
  options.threads = 1;
  options.candidates.ring_elevations_deg = {-20.0, 10.0, 40.0};
  objscan::planning::NextBestView nbv(options);
  double best_gain = 0.0;
  for (auto _ : state) {
    const objscan::planning::NextBestViewResult r = nbv.Plan(input, nullptr);
    best_gain = r.candidates[static_cast<std::size_t>(r.best_index)].gain.gain;
    benchmark::DoNotOptimize(r.best_index);
  }
  state.counters["unseen_voxels_in_best_view"] = best_gain;
}
BENCHMARK(BM_CoverageView)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_NextBestObject(benchmark::State& state) {
  objscan::Rng rng(3);
  std::vector<objscan::planning::NboObject> objects(static_cast<std::size_t>(state.range(0)));
  for (std::size_t i = 0; i < objects.size(); ++i) {
    objects[i].id = static_cast<int>(i);
    objects[i].objectness = rng.Uniform01();
    objects[i].center_world = Eigen::Vector3d(rng.Uniform(-5, 5), rng.Uniform(-5, 5), rng.Uniform(0, 1.5));
    objects[i].area_m2 = rng.Uniform(0.05, 3.0);
    objects[i].complete = rng.Bernoulli(0.2);
    objects[i].views_spent = rng.UniformInt(0, 5);
  }
  objscan::planning::RobotView robot;
  robot.view_direction_world = Eigen::Vector3d(1.0, 0.5, -0.3);
  const objscan::planning::NextBestObjectOptions options;
  for (auto _ : state) {
    benchmark::DoNotOptimize(objscan::planning::SelectNextBestObject(objects, robot, -1, options));
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_NextBestObject)->Arg(50)->Unit(benchmark::kMicrosecond);

}  // namespace
