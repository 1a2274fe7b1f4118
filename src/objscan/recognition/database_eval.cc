#include "objscan/recognition/database_eval.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <string>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"
#include "objscan/common/timer.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/common/parallel_for.h"
#include "objscan/world/procedural/procedural.h"

namespace objscan::recognition {

void DatabaseEvalOptions::Validate() const {
  config::Require(queries_per_category >= 0, "recognition.eval.queries_per_category", "must be >= 0 (0 = all)");
  config::Require(objectness_models_per_category >= 0, "recognition.eval.objectness_models_per_category",
                  "must be >= 0");
  config::RequireInRange("recognition.eval.min_elevation_deg", min_elevation_deg, -30.0, 89.0);
  config::RequireInRange("recognition.eval.max_elevation_deg", max_elevation_deg, min_elevation_deg, 89.0);
  config::RequireNonNegative("recognition.eval.threads", threads);
  config::Require(draws_per_model >= 1, "recognition.eval.draws_per_model", "must be at least 1");
  scan.Validate();
  recognition.Validate();
}

namespace {

// A random placement in the world: yaw about Z and a horizontal offset (the database frame is
// canonical, a query is not).
geometry::TriangleMesh RandomlyPlaced(const geometry::TriangleMesh& mesh, Rng* rng) {
  Eigen::Affine3d T = Eigen::Affine3d::Identity();
  T.translate(Eigen::Vector3d(rng->Uniform(-3, 3), rng->Uniform(-3, 3), 0.0));
  T.rotate(Eigen::AngleAxisd(rng->Uniform(-M_PI, M_PI), Eigen::Vector3d::UnitZ()));
  return geometry::Transformed(mesh, T);
}

geometry::PointCloud ScanViews(const geometry::TriangleMesh& mesh, int n_views, double step_rad,
                               const DatabaseEvalOptions& options, const VirtualScanOptions& scan, Rng* rng) {
  const geometry::Aabb3 bounds = geometry::Bounds(mesh);
  const double azimuth = rng->Uniform(-M_PI, M_PI);
  std::vector<geometry::Pose3> views;
  for (int v = 0; v < n_views; ++v) {
    const double elevation =
        geometry::DegToRad(rng->Uniform(options.min_elevation_deg, options.max_elevation_deg));
    views.push_back(ViewFrom(bounds, azimuth + v * step_rad, elevation, scan));
  }
  return ScanModel(mesh, views, scan, options.query_noise, rng).surface;
}

}  // namespace

std::vector<ModelSource> ProceduralQuerySources(const ModelDatabase& database, const DatabaseEvalOptions& options) {
  std::vector<ModelSource> sources;
  for (world::Category c : world::procedural::FurnitureCategories()) {
    const bool in_db = std::any_of(database.models().begin(), database.models().end(),
                                   [c](const DatabaseModel& m) { return m.category == c; });
    if (!in_db) continue;
    // 0 (all) means the default five: the generator has no end.
    const int n = options.queries_per_category > 0 ? options.queries_per_category : 5;
    for (int q = 0; q < n; ++q) {
      const std::uint64_t seed = world::procedural::DatabaseModelSeed(options.first_query_index + q);
      ModelSource s;
      s.category = c;
      s.name = std::string(world::CategoryName(c)) + "/query_" + std::to_string(q);
      s.source = "procedural/" + std::string(world::CategoryName(c)) + "/" + std::to_string(seed);
      s.load_mesh = [c, seed] { return world::procedural::GenerateFurniture(c, seed).mesh; };
      sources.push_back(std::move(s));
    }
  }
  if (sources.empty()) throw InputError("db eval: the database has no category the procedural generator makes");
  return sources;
}

DatabaseEvalResult EvaluateDatabase(const ModelDatabase& database, const DatabaseEvalOptions& options,
                                    const ProgressCallback& progress) {
  options.Validate();
  return EvaluateDatabase(database, ProceduralQuerySources(database, options), options, progress);
}

DatabaseEvalResult EvaluateDatabase(const ModelDatabase& database, const std::vector<ModelSource>& queries,
                                    const DatabaseEvalOptions& options, const ProgressCallback& progress) {
  options.Validate();
  const Recognizer recognizer(database, options.recognition);
  DatabaseEvalResult out;
  std::vector<const ModelSource*> sources;
  std::map<world::Category, int> taken;
  for (const ModelSource& s : queries) {
    const bool in_db = std::any_of(database.models().begin(), database.models().end(),
                                   [&s](const DatabaseModel& m) { return m.category == s.category; });
    if (!in_db) {
      out.skipped_queries.push_back(s.name);
      continue;
    }
    if (options.queries_per_category > 0 && taken[s.category] >= options.queries_per_category) continue;
    ++taken[s.category];
    sources.push_back(&s);
  }
  if (sources.empty()) throw InputError("db eval: no query model of a category the database holds");
  out.query_models = static_cast<int>(sources.size());

  {
    const Stopwatch train;
    out.classifier_max_depth = recognizer.classifier().max_depth();  // trained once, before the queries
    out.classifier_train_s = train.ElapsedMs() / 1000.0;
    out.classifier_cache = recognizer.classifier_cache_status();
  }
  const int workers = ResolveThreadCount(options.threads);
  VirtualScanOptions scan = options.scan;
  if (workers > 1) scan.sensor.threads = 1;

  // Recognition queries: (source, views).
  struct Task {
    const ModelSource* source;
    int views;
    bool piece;
    int draw;
  };
  std::vector<Task> tasks;
  for (int draw = 0; draw < options.draws_per_model; ++draw) {
    for (const ModelSource* s : sources) {
      for (int views : {1, 3}) tasks.push_back({s, views, false, draw});
      if (options.piece_queries) tasks.push_back({s, 1, true, draw});
    }
  }
  // Objectness tasks: database models scanned afresh.
  std::vector<int> objectness_models;
  {
    std::map<world::Category, int> taken;
    for (std::size_t m = 0; m < database.models().size(); ++m) {
      const world::Category c = database.models()[m].category;
      if (taken[c] < options.objectness_models_per_category) {
        ++taken[c];
        objectness_models.push_back(static_cast<int>(m));
      }
    }
  }
  const int n_tasks = static_cast<int>(tasks.size());
  const int n_total = n_tasks + static_cast<int>(objectness_models.size());

  struct TaskResult {
    world::Category predicted = world::Category::kOther;
    world::Category retrieved_category = world::Category::kOther;
    bool classified = false;
    world::Category classifier_choice = world::Category::kOther;
    CategoryClassifier::Probabilities posterior{};
    bool top1 = false, top5 = false;
    std::vector<DatabaseEvalResult::Retrieved> retrieved;
    double ms = 0.0, classify_ms = 0.0;
    double complete = 0.0, partial = 0.0;
  };
  std::vector<TaskResult> results(n_total);
  std::mutex progress_mutex;
  int done = 0;
  ParallelForBlocks(n_total, workers, [&](int t) {
    Rng rng(DeriveSeed(options.seed, static_cast<std::uint64_t>(t)));
    TaskResult& r = results[t];
    if (t < n_tasks) {
      const Task& task = tasks[t];
      // Normalised as the database builder normalises its models (metres, standing on z = 0).
      const geometry::TriangleMesh mesh = RandomlyPlaced(
          NormalizeModel(task.source->load_mesh(), TypicalHeight(task.source->category)), &rng);
      geometry::PointCloud surface =
          ScanViews(mesh, task.views, geometry::DegToRad(options.multi_view_step_deg), options, scan, &rng);
      if (task.piece) surface = HalfOf(surface, &rng);
      // The floor under the query: it stands where its model stands in its scene.
      const double floor_z =
          task.source->support_heights_m.empty() ? 0.0 : -static_cast<double>(task.source->support_heights_m.front());
      const Stopwatch watch;
      const QueryDescription query = recognizer.Describe(surface);
      const std::vector<SimilarModel> similar = recognizer.Retrieve(query, RetrievalScope::kFullModels);
      const Stopwatch classify;
      r.posterior = recognizer.CategoryPosterior(query, floor_z);
      r.classify_ms = classify.ElapsedMs();
      std::vector<RetrievedCategory> votes;
      for (const SimilarModel& s : similar) votes.push_back({database.entries()[s.entry].category, s.rank_score});
      const CategoryName name = NameCategory(r.posterior, votes, options.recognition.naming);
      r.ms = watch.ElapsedMs();
      r.classified = recognizer.classifier().trained();
      if (r.classified) {
        const auto best = std::max_element(r.posterior.begin(), r.posterior.end());
        r.classifier_choice = static_cast<world::Category>(best - r.posterior.begin());
      }
      if (!similar.empty()) r.retrieved_category = database.entries()[similar.front().entry].category;
      if (name.named) {
        r.predicted = name.category;
        r.top1 = r.predicted == task.source->category;
      }
      for (const auto& s : similar) r.top5 = r.top5 || database.entries()[s.entry].category == task.source->category;
      for (const SimilarModel& s : similar) {
        const DatabaseEntry& e = database.entries()[s.entry];
        r.retrieved.push_back({e.name, e.category, s.rank_score, s.bow_score, s.fit,
                               s.objectness.objectness, s.visible_objectness, s.query_inliers, s.model_inliers,
                               s.fscore});
      }
    } else {
      const DatabaseModel& model = database.models()[objectness_models[t - n_tasks]];
      const geometry::TriangleMesh mesh = RandomlyPlaced(LoadModelSourceMesh(model), &rng);
      // Complete: every ring view again, with noise and the ring turned by a random azimuth.
      std::vector<geometry::Pose3> views;
      const double turn = rng.Uniform(0.0, 2.0 * M_PI);
      const geometry::Aabb3 bounds = geometry::Bounds(mesh);
      for (std::size_t ring = 0; ring < scan.ring_elevations_deg.size(); ++ring) {
        const int n = static_cast<int>(scan.ring_views[ring]);
        for (int k = 0; k < n; ++k)
          views.push_back(ViewFrom(bounds, turn + 2.0 * M_PI * (k + 0.5 * (ring % 2)) / n,
                                   geometry::DegToRad(scan.ring_elevations_deg[ring]), scan));
      }
      const geometry::PointCloud complete = ScanModel(mesh, views, scan, options.query_noise, &rng).surface;
      const geometry::PointCloud partial = ScanViews(mesh, 1, 0.0, options, scan, &rng);
      r.complete = recognizer.Match(recognizer.Describe(complete), model.full_entry).objectness.objectness;
      r.partial = recognizer.Match(recognizer.Describe(partial), model.full_entry).objectness.objectness;
    }
    std::lock_guard<std::mutex> lock(progress_mutex);
    ++done;
    ReportProgress(progress, static_cast<double>(done) / n_total, "query");
  });

  double ms_sum = 0.0;
  for (const auto& [views, piece] : {std::pair<int, bool>{1, false}, {3, false}, {1, true}}) {
    ViewCountAccuracy acc;
    acc.views = views;
    acc.piece = piece;
    for (int t = 0; t < n_tasks; ++t) {
      if (tasks[t].views != views || tasks[t].piece != piece) continue;
      const world::Category truth = tasks[t].source->category;
      ++acc.queries;
      acc.top1_category_accuracy += results[t].top1 ? 1.0 : 0.0;
      acc.top5_category_accuracy += results[t].top5 ? 1.0 : 0.0;
      acc.retrieval_top1_accuracy += results[t].retrieved_category == truth ? 1.0 : 0.0;
      acc.classifier_top1_accuracy += results[t].classified && results[t].classifier_choice == truth ? 1.0 : 0.0;
      ms_sum += results[t].ms;
      DatabaseEvalResult::Query q;
      q.truth = truth;
      q.predicted = results[t].predicted;
      q.retrieved_category = results[t].retrieved_category;
      q.views = views;
      q.piece = piece;
      q.draw = tasks[t].draw;
      q.top5 = results[t].top5;
      q.model = tasks[t].source->name;
      q.retrieved = std::move(results[t].retrieved);
      q.classified = results[t].classified;
      q.classifier_choice = results[t].classifier_choice;
      q.posterior = results[t].posterior;
      out.queries.push_back(std::move(q));
    }
    if (acc.queries == 0) continue;
    acc.top1_category_accuracy /= acc.queries;
    acc.top5_category_accuracy /= acc.queries;
    acc.retrieval_top1_accuracy /= acc.queries;
    acc.classifier_top1_accuracy /= acc.queries;
    out.by_views.push_back(acc);
  }
  out.top1_category_accuracy = out.by_views[0].top1_category_accuracy;
  out.top5_category_accuracy = out.by_views[0].top5_category_accuracy;
  out.ms_per_query = n_tasks > 0 ? ms_sum / n_tasks : 0.0;
  for (int t = 0; t < n_tasks; ++t) out.classify_ms_per_query += results[t].classify_ms / n_tasks;
  out.objectness_models = static_cast<int>(objectness_models.size());
  for (int t = n_tasks; t < n_total; ++t) {
    out.objectness_complete_mean += results[t].complete;
    out.objectness_partial_mean += results[t].partial;
  }
  if (out.objectness_models > 0) {
    out.objectness_complete_mean /= out.objectness_models;
    out.objectness_partial_mean /= out.objectness_models;
  }
  return out;
}

}  // namespace objscan::recognition
