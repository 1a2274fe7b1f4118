// Benchmarks of recognition (paper §4.2): describing a query, retrieving M(c) from databases of
// 100, 400 and 1600 entries (the bag-of-words stage alone and the whole retrieval with alignment and
// objectness of the shortlist), aligning, objectness, Lloyd keypoints, FPFH histograms (ours and PCL's
// FPFHEstimation, the peer, on the same cloud and keypoints) and loading a database; with
// OBJSCAN_BENCH_DB set, describing and retrieving eval-like queries against that database.
// The larger databases replicate a database of analytic shapes with perturbed copies (histograms
// reweighted and thinned, keypoints scaled), so posting lists grow with the item count as they would.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <unistd.h>
#include <map>
#include <memory>
#include <random>

#include "objscan/common/rng.h"
#include "objscan/recognition/alignment.h"
#include "objscan/recognition/category_classifier.h"
#include "objscan/recognition/fpfh_descriptor.h"
#include "objscan/recognition/keypoints.h"
#include "objscan/recognition/objectness.h"
#include "objscan/recognition/recognizer.h"
#include "objscan/recognition/test_database.h"
#include "objscan/recognition/virtual_scan.h"
#include "objscan/recognition/vocabulary.h"
#include "objscan/world/procedural/procedural.h"

namespace {

using namespace objscan;
using namespace objscan::recognition;

const ModelDatabase& BaseDatabase() {
  static const ModelDatabase* db = new ModelDatabase(
      BuildDatabaseFromScans(testing::ShapeModels(0.012), testing::SmallDatabaseOptions()));
  return *db;
}

// `n` entries: the base entries followed by perturbed copies.
const ModelDatabase& ScaledDatabase(int n) {
  static std::map<int, std::unique_ptr<ModelDatabase>> cache;
  auto& slot = cache[n];
  if (slot) return *slot;
  const ModelDatabase& base = BaseDatabase();
  slot = std::make_unique<ModelDatabase>();
  ModelDatabase& db = *slot;
  db.mutable_settings() = base.settings();
  db.set_vocabulary(base.vocabulary());
  db.mutable_models() = base.models();
  Rng rng(42);
  const auto& src = base.entries();
  for (int i = 0; i < n; ++i) {
    DatabaseEntry e = src[i % src.size()];
    if (i >= static_cast<int>(src.size())) {
      // Copies are full models so both scopes grow (a full model holds its own points).
      if (e.kind != EntryKind::kFullModel) e.points = base.EntryPoints(static_cast<int>(i % src.size()));
      e.point_indices.clear();
      e.kind = EntryKind::kFullModel;
      SparseHistogram h;
      for (const auto& b : e.bow) {
        if (rng.Bernoulli(0.8)) h.push_back({b.bin, b.value * static_cast<float>(rng.Uniform(0.5, 1.5))});
      }
      e.bow = std::move(h);
      const float s = static_cast<float>(rng.Uniform(0.8, 1.25));
      for (auto& k : e.keypoints) k *= s;
      for (auto& p : e.points) p *= s;
      e.bounds = geometry::Aabb3();
    }
    db.mutable_entries().push_back(std::move(e));
  }
  db.Finalize();
  return db;
}

geometry::PointCloud ChairQuery() {
  geometry::PointCloud cloud;
  testing::ChairLike(0.01, &cloud.points, &cloud.normals);
  geometry::PointCloud partial;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cloud.normals[i].x() > 0.5f || cloud.normals[i].z() > 0.5f) {
      partial.points.push_back(cloud.points[i] + Eigen::Vector3f(1.5f, -0.7f, 0.f));
      partial.normals.push_back(cloud.normals[i]);
    }
  }
  return partial;
}

void BM_DescribeQuery(benchmark::State& state) {
  const Recognizer recognizer(BaseDatabase(), RecognitionOptions());
  const geometry::PointCloud query = ChairQuery();
  for (auto _ : state) benchmark::DoNotOptimize(recognizer.Describe(query));
}
BENCHMARK(BM_DescribeQuery)->Unit(benchmark::kMillisecond);

// The inverted-index stage alone: the shortlist of a described query.
void BM_RetrieveBow(benchmark::State& state) {
  const ModelDatabase& db = ScaledDatabase(static_cast<int>(state.range(0)));
  const Recognizer recognizer(db, RecognitionOptions());
  const QueryDescription q = recognizer.Describe(ChairQuery());
  for (auto _ : state) benchmark::DoNotOptimize(recognizer.Candidates(q, RetrievalScope::kAllEntries, 20));
  state.counters["items"] = static_cast<double>(db.entries().size());
}
BENCHMARK(BM_RetrieveBow)->Arg(100)->Arg(400)->Arg(1600)->Unit(benchmark::kMicrosecond);

// M(c) as callers get it: shortlist, alignment and objectness of each, top n_s.
void BM_Retrieve(benchmark::State& state) {
  const ModelDatabase& db = ScaledDatabase(static_cast<int>(state.range(0)));
  const Recognizer recognizer(db, RecognitionOptions());
  const QueryDescription q = recognizer.Describe(ChairQuery());
  for (auto _ : state) benchmark::DoNotOptimize(recognizer.Retrieve(q, RetrievalScope::kAllEntries));
  state.counters["items"] = static_cast<double>(db.entries().size());
}
BENCHMARK(BM_Retrieve)->Arg(100)->Arg(400)->Arg(1600)->Unit(benchmark::kMillisecond);

// The settings before the two-stage verification (every shortlist entry refined with all keypoints,
// 24 x 5 exact initial hypotheses on 96 points, 12 coarse, 3 refined): the ratio to BM_Retrieve /
// BM_Align in the same run is the speed-up.
RecognitionOptions LegacyOptions() {
  RecognitionOptions o;
  o.refine_entries = 0;
  AlignmentOptions& a = o.alignment;
  a.initial_points = 96;
  a.initial_truncation_m = 0.0;
  a.coarse_points = 96;
  a.coarse_keep = 12;
  a.coarse_iterations = 5;
  a.refine_hypotheses = 3;
  a.refine_iterations = 20;
  a.refine_points = 0;
  return o;
}

void BM_RetrieveLegacy(benchmark::State& state) {
  const ModelDatabase& db = ScaledDatabase(static_cast<int>(state.range(0)));
  const Recognizer recognizer(db, LegacyOptions());
  const QueryDescription q = recognizer.Describe(ChairQuery());
  for (auto _ : state) benchmark::DoNotOptimize(recognizer.Retrieve(q, RetrievalScope::kAllEntries));
  state.counters["items"] = static_cast<double>(db.entries().size());
}
BENCHMARK(BM_RetrieveLegacy)->Arg(1600)->Unit(benchmark::kMillisecond);

void BM_AlignLegacy(benchmark::State& state) {
  const ModelDatabase& db = BaseDatabase();
  const Recognizer recognizer(db, RecognitionOptions());
  const QueryDescription q = recognizer.Describe(ChairQuery());
  const AlignmentTarget& target = db.keypoint_target(db.models()[0].full_entry);
  const AlignmentOptions options = LegacyOptions().alignment;
  for (auto _ : state) benchmark::DoNotOptimize(AlignToItem(q.keypoints, target, options));
}
BENCHMARK(BM_AlignLegacy)->Unit(benchmark::kMillisecond);

void BM_Align(benchmark::State& state) {
  const ModelDatabase& db = BaseDatabase();
  const Recognizer recognizer(db, RecognitionOptions());
  const QueryDescription q = recognizer.Describe(ChairQuery());
  const AlignmentTarget& target = db.keypoint_target(db.models()[0].full_entry);
  const AlignmentOptions options;
  for (auto _ : state) benchmark::DoNotOptimize(AlignToItem(q.keypoints, target, options));
}
BENCHMARK(BM_Align)->Unit(benchmark::kMillisecond);

// The coarse stage alone on a database entry: arg 1 scores the initial hypotheses by the entry's
// distance grid (the default), arg 0 by kd-tree searches.
void BM_CoarseAlign(benchmark::State& state) {
  const ModelDatabase& db = BaseDatabase();
  const Recognizer recognizer(db, RecognitionOptions());
  const QueryDescription q = recognizer.Describe(ChairQuery());
  const AlignmentTarget& target = db.keypoint_target(db.models()[0].full_entry);
  AlignmentOptions options;
  options.grid_initial_scoring = state.range(0) == 1;
  for (auto _ : state) benchmark::DoNotOptimize(CoarseAlign(q.keypoints, target, options));
}
BENCHMARK(BM_CoarseAlign)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// Eq. (1) for n_p = 500 keypoints on both sides (kd-tree nearest neighbours both ways).
void BM_Objectness(benchmark::State& state) {
  const ModelDatabase& db = BaseDatabase();
  const auto& c = db.entries()[db.models()[0].full_entry].keypoints;
  const auto& m = db.entries()[db.models()[1].full_entry].keypoints;
  for (auto _ : state) benchmark::DoNotOptimize(ComputeObjectness(c, m, Eigen::Affine3d::Identity()));
}
BENCHMARK(BM_Objectness)->Unit(benchmark::kMicrosecond);

// Soft assignment of one FPFH-sized descriptor (33 bins) to a 128-word vocabulary, 3 words, as
// ComputeSpatialBow assigns every keypoint's descriptor. Arg 0: Vocabulary::Assign (all words'
// distances at once over the transposed words); arg 1: the word-by-word scalar loop it replaced,
// the peer (the same answer, checked by VocabularyTest.AssignmentIsExactlyTheWordByWordLoops).
void BM_VocabularyAssign(benchmark::State& state) {
  constexpr int kWords = 128, kDimension = 33;
  objscan::Rng rng(5);
  std::vector<float> words(static_cast<std::size_t>(kWords) * kDimension);
  for (auto& x : words) x = static_cast<float>(rng.Uniform(0.0, 0.4));
  const objscan::recognition::Vocabulary vocabulary(kDimension, words, 0.05f, 3);
  std::vector<std::vector<float>> queries(512, std::vector<float>(kDimension));
  for (auto& q : queries) {
    for (auto& x : q) x = static_cast<float>(rng.Uniform(0.0, 10.0));
  }
  const bool word_by_word = state.range(0) == 1;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::vector<float>& q = queries[i++ % queries.size()];
    if (!word_by_word) {
      objscan::recognition::WordAssignment out[8];
      benchmark::DoNotOptimize(vocabulary.Assign(q.data(), out));
      continue;
    }
    float x[kDimension];
    objscan::recognition::HellingerMap(q.data(), kDimension, x);
    float best_d2[3] = {1e30f, 1e30f, 1e30f};
    int best[3] = {-1, -1, -1};
    for (int w = 0; w < kWords; ++w) {
      float s = 0.f;
      for (int d = 0; d < kDimension; ++d) {
        const float e = x[d] - words[static_cast<std::size_t>(w) * kDimension + d];
        s += e * e;
      }
      if (s >= best_d2[2]) continue;
      int pos = 2;
      while (pos > 0 && best_d2[pos - 1] > s) {
        best_d2[pos] = best_d2[pos - 1];
        best[pos] = best[pos - 1];
        --pos;
      }
      best_d2[pos] = s;
      best[pos] = w;
    }
    benchmark::DoNotOptimize(best);
  }
}
BENCHMARK(BM_VocabularyAssign)->Arg(0)->Arg(1)->ArgName("word_by_word")->Unit(benchmark::kNanosecond);

void BM_LloydKeypoints(benchmark::State& state) {
  geometry::PointCloud cloud;
  testing::SofaLike(0.01, &cloud.points, &cloud.normals);
  const KeypointOptions options;
  for (auto _ : state) {
    Rng rng(1);
    benchmark::DoNotOptimize(SampleKeypointsLloyd(cloud.points, options, &rng));
  }
  state.counters["points"] = static_cast<double>(cloud.size());
}
BENCHMARK(BM_LloydKeypoints)->Unit(benchmark::kMillisecond);

// FPFH at 200 Lloyd keypoints of a sofa-like surface (1 cm spacing, 2 mm noise), the database
// builder's and the query's setting. Arg 0: our histograms; arg 1: PCL's FPFHEstimation (the peer).
// Both include the same PCA normals, thinning and keypoint lookup; only the histograms differ.
void BM_Fpfh(benchmark::State& state) {
  geometry::PointCloud cloud;
  std::vector<Eigen::Vector3f> keypoints;
  testing::NoisyShapeWithKeypoints(&testing::SofaLike, 200, &cloud, &keypoints);
  const FpfhDescriptor fpfh{DescriptorOptions()};
  const bool with_pcl = state.range(0) == 1;
  std::vector<float> descriptors;
  for (auto _ : state) {
    if (with_pcl) {
      fpfh.ComputeWithPcl(cloud, keypoints, &descriptors);
    } else {
      fpfh.Compute(cloud, keypoints, &descriptors);
    }
    benchmark::DoNotOptimize(descriptors.data());
  }
  state.SetLabel(with_pcl ? "pcl::FPFHEstimation" : "objscan");
  state.counters["points"] = static_cast<double>(cloud.size());
  state.counters["keypoints"] = static_cast<double>(keypoints.size());
}
BENCHMARK(BM_Fpfh)->Arg(0)->Arg(1)->ArgName("pcl")->Unit(benchmark::kMillisecond);

void BM_LoadDatabase(benchmark::State& state) {
  const ModelDatabase& db = ScaledDatabase(1600);
  const std::string path =
      (std::filesystem::temp_directory_path() / ("objscan_bench_" + std::to_string(::getpid()) + ".db")).string();
  db.Save(path);
  for (auto _ : state) benchmark::DoNotOptimize(ModelDatabase::Load(path));
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
  std::filesystem::remove(path);
}
BENCHMARK(BM_LoadDatabase)->Unit(benchmark::kMillisecond);

// The category recognizer: training on a database of n entries (its full models' views and half
// views, its components and pairs), both learners side by side; and naming one query (features and
// posterior) with a trained forest and with softmax regression.
void BM_TrainCategoryClassifier(benchmark::State& state) {
  const ModelDatabase& db = ScaledDatabase(static_cast<int>(state.range(0)));
  CategoryClassifierOptions options;
  options.method = state.range(1) == 0 ? "forest" : "softmax";
  options.forest.threads = 1;
  for (auto _ : state) benchmark::DoNotOptimize(CategoryClassifier::Train(db, options));
}
BENCHMARK(BM_TrainCategoryClassifier)
    ->Args({400, 0})
    ->Args({400, 1})
    ->ArgNames({"entries", "softmax"})
    ->Unit(benchmark::kMillisecond);

// Learners by index: 0 forest, 1 softmax, 2 point network, 3 forest + network (a short training:
// naming costs the same however long the network trained).
const char* const kClassifierMethods[] = {"forest", "softmax", "network", "forest+network"};

void BM_ClassifyCategory(benchmark::State& state) {
  const ModelDatabase& db = BaseDatabase();
  CategoryClassifierOptions options;
  options.method = kClassifierMethods[state.range(0)];
  options.forest.threads = 1;
  options.network.epochs = 1;
  options.network.threads = 1;
  const CategoryClassifier classifier = CategoryClassifier::Train(db, options);
  const DatabaseEntry& query = db.entries().front();
  for (auto _ : state) benchmark::DoNotOptimize(classifier.Classify(query.keypoints, query.keypoint_normals));
  state.counters["points"] = static_cast<double>(query.keypoints.size());
}
BENCHMARK(BM_ClassifyCategory)->DenseRange(0, 3)->ArgName("method")->Unit(benchmark::kMicrosecond);

}  // namespace

// Eval-like queries against a real database (set OBJSCAN_BENCH_DB to its path, e.g. the default
// procedural database; skipped otherwise): one noisy single view of an unseen procedural model per
// furniture category, randomly placed; each iteration describes (or retrieves) the next query.
namespace {

struct RealQueries {
  std::unique_ptr<ModelDatabase> db;
  std::vector<geometry::PointCloud> clouds;
  std::vector<QueryDescription> described;
};

const RealQueries* LoadRealQueries() {
  static const RealQueries* queries = [] {
    const char* path = std::getenv("OBJSCAN_BENCH_DB");
    if (!path) return static_cast<RealQueries*>(nullptr);
    auto* q = new RealQueries;
    q->db = std::make_unique<ModelDatabase>(ModelDatabase::Load(path));
    const VirtualScanOptions scan;
    Rng rng(11);
    for (world::Category c : world::procedural::FurnitureCategories()) {
      geometry::TriangleMesh mesh = NormalizeModel(
          world::procedural::GenerateFurniture(c, world::procedural::DatabaseModelSeed(2000000 + q->clouds.size())).mesh,
          1.0);
      Eigen::Affine3d T = Eigen::Affine3d::Identity();
      T.translate(Eigen::Vector3d(rng.Uniform(-3, 3), rng.Uniform(-3, 3), 0.0));
      T.rotate(Eigen::AngleAxisd(rng.Uniform(-M_PI, M_PI), Eigen::Vector3d::UnitZ()));
      mesh = geometry::Transformed(mesh, T);
      const geometry::Pose3 view =
          ViewFrom(geometry::Bounds(mesh), rng.Uniform(-M_PI, M_PI), geometry::DegToRad(rng.Uniform(15, 45)), scan);
      q->clouds.push_back(ScanModel(mesh, {view}, scan, true, &rng).surface);
    }
    const Recognizer recognizer(*q->db, RecognitionOptions());
    for (const auto& cloud : q->clouds) q->described.push_back(recognizer.Describe(cloud));
    return q;
  }();
  return queries;
}

void BM_RealDescribe(benchmark::State& state) {
  const RealQueries* q = LoadRealQueries();
  if (!q) {
    state.SkipWithError("OBJSCAN_BENCH_DB not set");
    return;
  }
  const Recognizer recognizer(*q->db, RecognitionOptions());
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(recognizer.Describe(q->clouds[i++ % q->clouds.size()]));
}
BENCHMARK(BM_RealDescribe)->Unit(benchmark::kMillisecond);

// arg 0: full models (as db eval), 1: all entries (as component queries).
void BM_RealRetrieve(benchmark::State& state) {
  const RealQueries* q = LoadRealQueries();
  if (!q) {
    state.SkipWithError("OBJSCAN_BENCH_DB not set");
    return;
  }
  const Recognizer recognizer(*q->db, RecognitionOptions());
  const RetrievalScope scope = state.range(0) == 0 ? RetrievalScope::kFullModels : RetrievalScope::kAllEntries;
  for (const auto& d : q->described) recognizer.Retrieve(d, scope);  // warm the lazily built grids
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(recognizer.Retrieve(q->described[i++ % q->described.size()], scope));
}
BENCHMARK(BM_RealRetrieve)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

// ICP correspondences (alignment.h): arg 0 the kd-tree only and every round run (the behaviour
// before the nearest grid: grid_correspondences and stop_when_correspondences_repeat off), arg 1
// the defaults; the ratio in one run is the speed-up. BM_NearestGridBuild is the one-off cost of a
// database entry's grid on its first use.
namespace {

void BM_AlignCorrespondences(benchmark::State& state) {
  const ModelDatabase& db = BaseDatabase();
  const Recognizer recognizer(db, RecognitionOptions());
  const QueryDescription q = recognizer.Describe(ChairQuery());
  const AlignmentTarget& target = db.keypoint_target(db.models()[0].full_entry);
  AlignmentOptions options;
  options.grid_correspondences = state.range(0) == 1;
  options.stop_when_correspondences_repeat = state.range(0) == 1;
  for (auto _ : state) benchmark::DoNotOptimize(AlignToItem(q.keypoints, target, options));
}
BENCHMARK(BM_AlignCorrespondences)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The exact nearest keypoint of a query `distance_cm` (arg 1) from a box's surface of arg 2 points,
// with a near-exact hint, as ICP asks it for points outside the nearest grid's band: walking by split
// planes (arg 0 = 1), by the nodes' boxes (2) or as kAuto chooses (0).
void BM_NearestBoundedFar(benchmark::State& state) {
  std::mt19937 rng(7);
  std::normal_distribution<float> gauss(0.f, 1.f);
  // Keypoints on the surface of a 1.0 x 0.6 x 0.9 m box (a cabinet's size), arg 2 of them.
  std::vector<Eigen::Vector3f> keypoints;
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  const Eigen::Vector3f size(1.0f, 0.6f, 0.9f);
  while (static_cast<int>(keypoints.size()) < state.range(2)) {
    Eigen::Vector3f p(unit(rng), unit(rng), unit(rng));
    const int face = static_cast<int>(unit(rng) * 6.f) % 6;
    p[face / 2] = static_cast<float>(face % 2);
    keypoints.push_back(p.cwiseProduct(size));
  }
  const KdTree3 tree(keypoints);
  const float distance_m = static_cast<float>(state.range(1)) / 100.f;
  struct Query {
    Eigen::Vector3f q;
    float bound_d2;
    int hint;
  };
  std::vector<Query> queries;
  for (std::size_t k = 0; k < 512; ++k) {
    const Eigen::Vector3f dir = Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Eigen::Vector3f q = keypoints[(k * 7919) % keypoints.size()] + distance_m * dir;
    // The hint: the nearest point of the query moved by 2 cm (the last ICP round's correspondence).
    float unused = 0.f;
    const int hint = tree.Nearest(q + 0.02f * Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng)).normalized(), &unused);
    queries.push_back({q, (keypoints[hint] - q).squaredNorm(), hint});
  }
  const auto walk = static_cast<KdTree3::Walk>(state.range(0));
  std::size_t i = 0;
  for (auto _ : state) {
    const Query& x = queries[i++ % queries.size()];
    float d2 = 0.f;
    benchmark::DoNotOptimize(tree.NearestBounded(x.q, x.bound_d2, x.hint, &d2, walk));
  }
  state.counters["points"] = static_cast<double>(keypoints.size());
}
BENCHMARK(BM_NearestBoundedFar)
    ->ArgsProduct({{0, 1, 2}, {2, 10, 20, 40, 80}, {500, 4000}})
    ->ArgNames({"walk", "cm", "points"})
    ->Unit(benchmark::kNanosecond);

void BM_NearestGridBuild(benchmark::State& state) {
  const ModelDatabase& db = BaseDatabase();
  const auto& keypoints = db.entries()[db.models()[0].full_entry].keypoints;
  std::size_t bytes = 0;
  for (auto _ : state) {
    const NearestGrid grid(keypoints, AlignmentTarget::kNearestGridBandM, AlignmentTarget::kNearestGridMaxCells,
                           AlignmentTarget::kNearestGridMinCellM);
    bytes = grid.memory_bytes();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["bytes"] = static_cast<double>(bytes);
  state.counters["points"] = static_cast<double>(keypoints.size());
}
BENCHMARK(BM_NearestGridBuild)->Unit(benchmark::kMicrosecond);

}  // namespace
