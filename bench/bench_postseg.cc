// Benchmarks of post-segmentation (multi-class graph cuts over 100 pre-segmented components):
// a cold step (empty cache: every component, pair and group is matched) against a warm step in which
// 10 components changed. The matcher answers from precomputed tables; with objectness_work:1 it also
// does the work of one objectness evaluation per query (eq. (1): both directed chamfer terms between
// n_p = 500 keypoint sets, brute force), a lower bound on the cost of a real query (which evaluates
// n_s = 5 models after retrieval), so the cold/warm ratio shows what the caching saves.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <vector>

#include "objscan/common/rng.h"
#include "objscan/segmentation/alpha_expansion.h"
#include "objscan/segmentation/post_segmenter.h"

namespace {

using objscan::segmentation::ComponentMatcher;
using objscan::segmentation::MatchResult;
using objscan::segmentation::MatchScope;
using objscan::segmentation::ModelMatch;
using objscan::world::Category;

constexpr int kGrid = 10;  // 10 x 10 components, 2 x 2 blocks are true objects (25 objects)

int ObjectOf(std::int32_t id) { return (id / kGrid / 2) * (kGrid / 2) + (id % kGrid) / 2; }

// n_s = 5 matches per query: the true category with objectness from similarity and completeness, and
// four decoys of other categories with lower scores, so the graph cut sees many labels.
class TableMatcher : public ComponentMatcher {
 public:
  static constexpr int kKeypoints = 500;

  explicit TableMatcher(bool objectness_work) : objectness_work_(objectness_work) {
    objscan::Rng rng(5);
    keypoints_.resize(static_cast<std::size_t>(kGrid * kGrid + 1) * kKeypoints * 3);
    for (float& x : keypoints_) x = static_cast<float>(rng.Uniform01());
    for (std::int32_t a = 0; a < kGrid * kGrid; ++a) {
      all_entries_[{a}] = Compute({a}, MatchScope::kAllEntries);
      for (std::int32_t b : {a + 1, a + kGrid}) {
        if ((b == a + 1 && a % kGrid == kGrid - 1) || b >= kGrid * kGrid) continue;
        all_entries_[{a, b}] = Compute({a, b}, MatchScope::kAllEntries);
      }
    }
  }

  MatchResult Match(const std::vector<std::int32_t>& ids, MatchScope scope) override {
    ++calls;
    if (objectness_work_) sink += Chamfer(ids.front(), kGrid * kGrid) + Chamfer(kGrid * kGrid, ids.front());
    if (scope == MatchScope::kAllEntries) {
      auto it = all_entries_.find(ids);
      if (it != all_entries_.end()) return it->second;
    }
    return Compute(ids, scope);
  }

  long calls = 0;
  double sink = 0.0;

 private:
  // d(X, Y) of the paper between keypoint set a and keypoint set b.
  double Chamfer(int a, int b) const {
    const float* x = &keypoints_[static_cast<std::size_t>(a) * kKeypoints * 3];
    const float* y = &keypoints_[static_cast<std::size_t>(b) * kKeypoints * 3];
    double sum = 0.0;
    for (int i = 0; i < kKeypoints; ++i) {
      float best = 1e30f;
      for (int j = 0; j < kKeypoints; ++j) {
        const float dx = x[3 * i] - y[3 * j];
        const float dy = x[3 * i + 1] - y[3 * j + 1];
        const float dz = x[3 * i + 2] - y[3 * j + 2];
        best = std::min(best, dx * dx + dy * dy + dz * dz);
      }
      sum += best;
    }
    return sum / kKeypoints;
  }

  static MatchResult Compute(const std::vector<std::int32_t>& ids, MatchScope scope) {
    std::map<int, int> count;
    for (std::int32_t id : ids) ++count[ObjectOf(id)];
    auto best = std::max_element(count.begin(), count.end(),
                                 [](const auto& x, const auto& y) { return x.second < y.second; });
    const int object = best->first;
    const double similarity = static_cast<double>(best->second) / static_cast<double>(ids.size());
    const double completeness = static_cast<double>(best->second) / 4.0;
    const double o = scope == MatchScope::kFullModels ? 0.98 * similarity * similarity * completeness
                                                      : (similarity == 1.0 ? 0.8 : 0.8 * similarity * similarity);
    MatchResult r;
    for (int k = 0; k < 5; ++k) {
      ModelMatch m;
      m.category = static_cast<Category>((object * 3 + k * 5) % objscan::world::kNumObjectCategories);
      m.model_id = object * 5 + k;
      m.entry_id = m.model_id;
      m.full_model = scope == MatchScope::kFullModels;
      m.objectness = o * (1.0 - 0.15 * k);
      r.models.push_back(m);
    }
    return r;
  }

  bool objectness_work_ = false;
  std::vector<float> keypoints_;  // per component, then one model: kKeypoints x 3, flat
  std::map<std::vector<std::int32_t>, MatchResult> all_entries_;
};

objscan::segmentation::PostSegmenterInput GridInput() {
  objscan::segmentation::PostSegmenterInput input;
  for (std::int32_t id = 0; id < kGrid * kGrid; ++id) {
    input.components.push_back({id, 1});
    if (id % kGrid != kGrid - 1) input.edges.emplace_back(id, id + 1);
    if (id + kGrid < kGrid * kGrid) input.edges.emplace_back(id, id + kGrid);
  }
  return input;
}

objscan::segmentation::PostSegmenterOptions Options(const benchmark::State& state) {
  objscan::segmentation::PostSegmenterOptions options;
  options.split_instances = state.range(0) != 0;
  return options;
}

void BM_PostSegmentCold(benchmark::State& state) {
  TableMatcher matcher(state.range(1) != 0);
  const auto input = GridInput();
  std::size_t objects = 0;
  for (auto _ : state) {
    objscan::segmentation::PostSegmenter segmenter(Options(state), &matcher);
    const auto seg = segmenter.Update(input);
    objects = seg.objects.size();
    benchmark::DoNotOptimize(seg.energy);
  }
  state.counters["objects"] = static_cast<double>(objects);
  state.counters["matcher_calls"] = static_cast<double>(matcher.calls) / static_cast<double>(state.iterations());
  benchmark::DoNotOptimize(matcher.sink);
}
BENCHMARK(BM_PostSegmentCold)
    ->ArgNames({"split", "objectness_work"})
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

void BM_PostSegmentWarm10Changed(benchmark::State& state) {
  TableMatcher matcher(state.range(1) != 0);
  auto input = GridInput();
  objscan::segmentation::PostSegmenter segmenter(Options(state), &matcher);
  segmenter.Update(input);
  matcher.calls = 0;
  std::uint64_t revision = 1;
  std::size_t objects = 0;
  for (auto _ : state) {
    ++revision;
    for (int j = 0; j < 10; ++j) input.components[static_cast<std::size_t>(j * 10 + j % 10)].revision = revision;
    const auto seg = segmenter.Update(input);
    objects = seg.objects.size();
    benchmark::DoNotOptimize(seg.energy);
  }
  state.counters["objects"] = static_cast<double>(objects);
  state.counters["matcher_calls"] = static_cast<double>(matcher.calls) / static_cast<double>(state.iterations());
  benchmark::DoNotOptimize(matcher.sink);
}
BENCHMARK(BM_PostSegmentWarm10Changed)
    ->ArgNames({"split", "objectness_work"})
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// The graph cut alone on the same graph size: 100 nodes, 180 edges, 23 labels.
void BM_AlphaExpansion100Nodes(benchmark::State& state) {
  const auto input = GridInput();
  objscan::segmentation::PottsEnergy energy(kGrid * kGrid, objscan::world::kNumObjectCategories + 1);
  for (int p = 0; p < kGrid * kGrid; ++p) {
    for (int l = 0; l < energy.num_labels(); ++l) {
      energy.SetDataCost(p, l, 0.2 + 0.8 * static_cast<double>((p * 7 + l * 13) % 17) / 16.0);
    }
  }
  for (const auto& [a, b] : input.edges) energy.AddEdge(a, b, ObjectOf(a) == ObjectOf(b) ? 0.8 : 0.2);
  for (auto _ : state) {
    benchmark::DoNotOptimize(objscan::segmentation::MinimizeByAlphaExpansion(energy).energy);
  }
}
BENCHMARK(BM_AlphaExpansion100Nodes)->Unit(benchmark::kMicrosecond);

}  // namespace
