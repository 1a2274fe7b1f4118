// `objscan db`: build, inspect and evaluate the 3D model database (paper §4.2).
//   objscan db build --models DIR|WORLD...|procedural|sweethome3d|X.sh3f --out F.db -> JSON summary on stdout
//   objscan db info F.db                                  -> JSON counts and model sizes per category
//   objscan db eval --db F.db [--queries procedural|DIR|WORLD...] -> JSON accuracy, objectness, timing
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "cli_util.h"
#include "commands.h"
#include "objscan/common/config.h"
#include "objscan/common/error.h"
#include "objscan/common/timer.h"
#include "objscan/eval/benchmark.h"
#include "objscan/io/category_map.h"
#include "objscan/io/scannet.h"
#include "objscan/io/sweethome3d.h"
#include "objscan/io/scene_spec.h"
#include "objscan/recognition/category_extent.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/recognition/database_eval.h"
#include "objscan/recognition/model_database.h"
#include "objscan/recognition/sweethome3d_sources.h"

namespace objscan::app {
namespace {

struct DbArgs {
  std::vector<std::string> models;
  std::vector<std::string> model_path;
  std::string category_map;
  std::string out;
  std::string info_db;
  std::string eval_db;
  std::vector<std::string> queries{"procedural"};
  int variants = 8;
  std::string sampling = "style-medoids";  // as the built-in database
  int queries_per_category = 5;
  int draws = 1;
  int threads = 0;
  std::uint64_t seed = 1;
  std::vector<std::string> sets;
};

template <class Options>
void ApplySets(const std::vector<std::string>& sets, Options* options) {
  config::RawConfig raw;
  for (const auto& s : sets) raw.SetFromAssignment(s);
  config::Apply(raw, options);
}

// The models named by `specs` (--models of build, --queries of eval), in the order given: 'procedural'
// (the built-in generator's models, --variants per category), model folders, and scenes (Gazebo
// worlds, ScanNet scans, ...) whose categorised objects are taken once per model id. Mixing them
// builds, e.g., the built-in models together with a user's own. 'sweethome3d' (every catalog of
// $OBJSCAN_SWEETHOME3D_DIR or /usr/share/sweethome3d/furniture) and X.sh3f take Sweet Home 3D
// furniture catalogs through --category-map or config/categories/sweethome3d.yaml; what they leave
// out goes to *sh3d (or, when it is null, a count to stderr).
std::vector<recognition::ModelSource> ModelSourcesFrom(const std::vector<std::string>& specs, const DbArgs& a,
                                                       const char* option, std::vector<std::string>* skipped,
                                                       recognition::SweetHome3dSources* sh3d = nullptr) {
  std::vector<recognition::ModelSource> sources;
  namespace fs = std::filesystem;
  io::SceneLoadOptions load;
  load.model_path = JoinModelPath(a.model_path);
  if (!a.category_map.empty()) load.category_map = a.category_map;
  std::vector<eval::WorldModels> worlds;
  const auto add_worlds = [&]() {
    if (worlds.empty()) return;
    const std::vector<recognition::ModelSource> from_worlds = eval::ModelDisjointSources(worlds, worlds.size());
    if (from_worlds.empty()) {
      throw InputError(std::string(option) + " " + worlds.front().world_path + ": no categorised object in the given scenes");
    }
    sources.insert(sources.end(), from_worlds.begin(), from_worlds.end());
    worlds.clear();
  };
  for (const std::string& spec : specs) {
    if (spec == "procedural") {
      add_worlds();
      if (a.variants < 1) throw InputError("--variants must be at least 1");
      const std::vector<recognition::ModelSource> generated = recognition::ProceduralModelSources(
          a.variants, 0, recognition::ParseProceduralSampling(a.sampling, "--sampling"));
      sources.insert(sources.end(), generated.begin(), generated.end());
    } else if (recognition::IsSweetHome3dSpec(spec)) {
      add_worlds();
      const io::CategoryMap map = io::CategoryMap::Load(io::ResolveCategoryMapPath(
          a.category_map.empty() ? std::string(recognition::kSweetHome3dCategoryMap) : a.category_map));
      recognition::SweetHome3dSources from_catalogs =
          recognition::SweetHome3dModelSources(recognition::SweetHome3dCatalogsOf(spec), map);
      if (from_catalogs.sources.empty()) {
        throw InputError(std::string(option) + " " + spec + ": no piece of furniture has a category in " + map.path());
      }
      sources.insert(sources.end(), from_catalogs.sources.begin(), from_catalogs.sources.end());
      if (sh3d == nullptr) {
        if (!from_catalogs.skipped.empty() || !from_catalogs.unmatched.empty()) {
          std::fprintf(stderr, "objscan: %s: %zu Sweet Home 3D pieces left out (%zu by skip rules, %zu matched no rule of %s)\n",
                       spec.c_str(), from_catalogs.skipped.size() + from_catalogs.unmatched.size(),
                       from_catalogs.skipped.size(), from_catalogs.unmatched.size(), map.path().c_str());
        }
      } else {
        from_catalogs.sources.clear();
        for (auto& c : from_catalogs.catalogs) sh3d->catalogs.push_back(std::move(c));
        sh3d->skipped.insert(sh3d->skipped.end(), from_catalogs.skipped.begin(), from_catalogs.skipped.end());
        sh3d->unmatched.insert(sh3d->unmatched.end(), from_catalogs.unmatched.begin(), from_catalogs.unmatched.end());
        for (const auto& [category, n] : from_catalogs.models_per_category) sh3d->models_per_category[category] += n;
      }
    } else if (fs::is_directory(spec) && !io::IsScanNetSpec(spec)) {
      add_worlds();
      const std::vector<recognition::ModelSource> folder = recognition::ModelSourcesFromFolder(spec, skipped);
      sources.insert(sources.end(), folder.begin(), folder.end());
    } else {
      worlds.push_back({spec, io::LoadScene(spec, load)});
    }
  }
  add_worlds();
  return sources;
}

int RunBuild(const DbArgs& a) {
  recognition::DatabaseBuildOptions options;
  options.threads = a.threads;
  options.seed = a.seed;
  ApplySets(a.sets, &options);
  std::vector<std::string> skipped;
  recognition::SweetHome3dSources sh3d;
  const std::vector<recognition::ModelSource> sources = ModelSourcesFrom(a.models, a, "--models", &skipped, &sh3d);
  const Stopwatch watch;
  const recognition::ModelDatabase db =
      recognition::BuildDatabase(sources, options, TerminalProgress("db build"));
  FinishProgress();
  db.Save(a.out);
  nlohmann::json j;
  j["out"] = a.out;
  j["models"] = db.models().size();
  j["entries"] = db.entries().size();
  j["models_without_points"] = sources.size() - db.models().size();
  j["skipped_folders"] = skipped;
  if (!sh3d.catalogs.empty()) {
    nlohmann::json catalogs = nlohmann::json::array();
    for (const auto& c : sh3d.catalogs) {
      catalogs.push_back({{"file", c.file}, {"name", c.name}, {"license", c.license}, {"license_text", c.license_text},
                          {"pieces", c.pieces}, {"models", c.models}});
    }
    j["sweethome3d"] = {{"catalogs", catalogs},
                        {"models_per_category", sh3d.models_per_category},
                        {"left_out_by_skip_rules", sh3d.skipped.size()},
                        {"left_out_unmatched", sh3d.unmatched.size()},
                        {"skipped", sh3d.skipped},
                        {"unmatched", sh3d.unmatched}};
  }
  j["seconds"] = watch.ElapsedSeconds();
  std::printf("%s\n", j.dump(2).c_str());
  return 0;
}

int RunInfo(const DbArgs& a) {
  const Stopwatch watch;
  const recognition::ModelDatabase db = recognition::ModelDatabase::Load(a.info_db);
  const double load_ms = watch.ElapsedMs();
  std::map<std::string, std::map<std::string, int>> counts;
  for (const auto& e : db.entries()) {
    auto& c = counts[world::CategoryName(e.category)];
    c["models"] += e.kind == recognition::EntryKind::kFullModel ? 1 : 0;
    c["components"] += e.kind == recognition::EntryKind::kComponent ? 1 : 0;
    c["pairs"] += e.kind == recognition::EntryKind::kPair ? 1 : 0;
  }
  // Model sizes per category: what the size-plausibility check of recognized objects compares with.
  const recognition::CategoryExtents extents = recognition::CategoryExtents::FromDatabase(db);
  nlohmann::json sizes = nlohmann::json::object();
  for (int c = 0; c < world::kNumObjectCategories; ++c) {
    const recognition::ExtentRange* r = extents.Find(static_cast<world::Category>(c));
    if (r == nullptr) continue;
    sizes[world::CategoryName(static_cast<world::Category>(c))] = {
        {"height_m", {r->min.height_m, r->max.height_m}},
        {"footprint_diagonal_m", {r->min.footprint_diagonal_m, r->max.footprint_diagonal_m}}};
  }
  nlohmann::json j;
  j["file"] = a.info_db;
  j["format_version"] = recognition::ModelDatabase::kFormatVersion;
  j["models"] = db.models().size();
  j["entries"] = db.entries().size();
  j["categories"] = counts;
  j["model_sizes"] = sizes;
  // Meshes stored with the models (format 5): what db eval and models.ply draw without the sources.
  std::size_t models_with_mesh = 0, mesh_triangles = 0;
  for (const auto& m : db.models()) {
    models_with_mesh += m.mesh.Empty() ? 0 : 1;
    mesh_triangles += m.mesh.NumTriangles();
  }
  j["stored_meshes"] = {{"models", models_with_mesh}, {"triangles", mesh_triangles}};
  j["vocabulary_words"] = db.vocabulary().num_words();
  j["keypoints_per_entry"] = db.settings().keypoints.num_keypoints;
  j["descriptor"] = db.settings().descriptor.type;
  // Credits: models made by someone (Sweet Home 3D catalogs), per catalog, creator and licence.
  std::map<std::tuple<std::string, std::string, std::string>, int> credit_counts;
  for (const auto& m : db.models()) {
    if (m.creator.empty() && m.license.empty()) continue;
    const std::string catalog = io::SweetHome3dSourceCatalog(m.source);
    ++credit_counts[{catalog.empty() ? std::string() : std::filesystem::path(catalog).filename().string(), m.creator,
                     m.license}];
  }
  nlohmann::json credits = nlohmann::json::array();
  for (const auto& [key, n] : credit_counts) {
    credits.push_back({{"catalog", std::get<0>(key)}, {"creator", std::get<1>(key)}, {"license", std::get<2>(key)},
                       {"models", n}});
  }
  j["credits"] = credits;
  j["load_ms"] = load_ms;
  std::printf("%s\n", j.dump(2).c_str());
  return 0;
}

int RunEval(const DbArgs& a) {
  recognition::DatabaseEvalOptions options;
  options.queries_per_category = a.queries_per_category;
  options.draws_per_model = a.draws;
  options.threads = a.threads;
  ApplySets(a.sets, &options);
  const bool procedural = a.queries.size() == 1 && a.queries.front() == "procedural";
  // --db default: the database `objscan run` uses for the queries' scenes (procedural ones for the
  // generator's models, the real one for every other source).
  const std::string db_path =
      a.eval_db != "default" ? a.eval_db : DefaultDatabasePathFor(procedural ? "procedural:" : "", true);
  const recognition::ModelDatabase db = recognition::ModelDatabase::Load(db_path);
  std::vector<std::string> skipped_folders;
  if (!procedural && std::find(a.queries.begin(), a.queries.end(), "procedural") != a.queries.end()) {
    throw InputError("--queries procedural (unseen generator models) cannot be combined with other queries");
  }
  const std::vector<recognition::ModelSource> queries =
      procedural ? recognition::ProceduralQuerySources(db, options)
                 : ModelSourcesFrom(a.queries, a, "--queries", &skipped_folders);
  options.recognition.classifier.extra_training_databases =
      TrainingDatabasePaths(options.recognition.classifier.extra_training_databases, true);
  const recognition::DatabaseEvalResult r =
      recognition::EvaluateDatabase(db, queries, options, TerminalProgress("db eval"));
  FinishProgress();
  ReportClassifierCache(r.classifier_cache);
  nlohmann::json j;
  j["top1_category_accuracy"] = r.top1_category_accuracy;
  j["top5_category_accuracy"] = r.top5_category_accuracy;
  j["objectness_complete_mean"] = r.objectness_complete_mean;
  j["objectness_partial_mean"] = r.objectness_partial_mean;
  j["ms_per_query"] = r.ms_per_query;
  j["classifier_train_s"] = r.classifier_train_s;
  j["classifier_max_depth"] = r.classifier_max_depth;
  j["classify_ms_per_query"] = r.classify_ms_per_query;
  // The naming options the names were given with: recognition_summary.py re-decides names from them.
  const recognition::CategoryNamingOptions& naming = options.recognition.naming;
  j["naming"] = {{"classifier_weight", naming.classifier_weight},
                 {"absent_share", naming.absent_share},
                 {"other_weight", naming.other_weight}};
  nlohmann::json by_views = nlohmann::json::array();
  for (const auto& v : r.by_views) {
    // Per category: top-1 of the name given, over the queries of that kind.
    std::map<std::string, std::pair<int, int>> per_category;  // truth -> (right, queries)
    std::map<std::string, std::map<std::string, int>> confusion;  // truth -> predicted -> count
    for (const auto& q : r.queries) {
      if (q.views != v.views || q.piece != v.piece) continue;
      auto& c = per_category[world::CategoryName(q.truth)];
      c.first += q.truth == q.predicted ? 1 : 0;
      ++c.second;
      ++confusion[world::CategoryName(q.truth)][world::CategoryName(q.predicted)];
    }
    nlohmann::json categories = nlohmann::json::object();
    for (const auto& [name, c] : per_category) {
      categories[name] = {{"queries", c.second}, {"top1", static_cast<double>(c.first) / c.second}};
    }
    by_views.push_back({{"views", v.views},
                        {"piece", v.piece},
                        {"queries", v.queries},
                        {"top1_category_accuracy", v.top1_category_accuracy},
                        {"top5_category_accuracy", v.top5_category_accuracy},
                        {"retrieval_top1_accuracy", v.retrieval_top1_accuracy},
                        {"classifier_top1_accuracy", v.classifier_top1_accuracy},
                        {"per_category", categories},
                        {"confusion", confusion}});
  }
  j["by_views"] = by_views;
  j["objectness_models"] = r.objectness_models;
  std::map<std::string, std::map<std::string, int>> confusion;  // single views: truth -> predicted
  for (const auto& q : r.queries) {
    if (q.views == 1 && !q.piece) ++confusion[world::CategoryName(q.truth)][world::CategoryName(q.predicted)];
  }
  j["single_view_confusion"] = confusion;
  j["query_models"] = r.query_models;
  j["skipped_queries"] = r.skipped_queries;  // of a category the database lacks
  j["skipped_folders"] = skipped_folders;
  nlohmann::json per_query = nlohmann::json::array();
  for (const auto& q : r.queries) {
    nlohmann::json retrieved = nlohmann::json::array();
    for (const auto& m : q.retrieved) {
      retrieved.push_back({{"model", m.model},
                           {"category", world::CategoryName(m.category)},
                           {"rank_score", m.rank_score},
                           {"bow", m.bow},
                           {"fit", m.fit},
                           {"objectness", m.objectness},
                           {"visible_objectness", m.visible_objectness},
                           {"query_inliers", m.query_inliers},
                           {"model_inliers", m.model_inliers},
                           {"fscore", m.fscore}});
    }
    per_query.push_back({{"model", q.model},
                         {"views", q.views},
                         {"piece", q.piece},
                         {"draw", q.draw},
                         {"truth", world::CategoryName(q.truth)},
                         {"predicted", world::CategoryName(q.predicted)},
                         {"retrieval", world::CategoryName(q.retrieved_category)},
                         {"top5", q.top5},
                         {"retrieved", retrieved}});
    if (q.classified) {
      per_query.back()["classifier"] = world::CategoryName(q.classifier_choice);
      nlohmann::json posterior = nlohmann::json::object();
      for (int k = 0; k < world::kNumObjectCategories; ++k) {
        if (q.posterior[static_cast<std::size_t>(k)] > 0.0) {
          posterior[world::CategoryName(static_cast<world::Category>(k))] = q.posterior[static_cast<std::size_t>(k)];
        }
      }
      per_query.back()["posterior"] = posterior;
    }
  }
  j["queries"] = per_query;
  std::printf("%s\n", j.dump(2).c_str());
  return 0;
}

}  // namespace

void AddDbCommand(CLI::App& root, RunFn* run) {
  auto args = std::make_shared<DbArgs>();
  auto* cmd = root.add_subcommand("db", "Build, inspect and evaluate the 3D model database");
  auto* build = cmd->add_subcommand("build", "Build a model database from a folder of models or procedurally");
  build->add_option("--models", args->models,
                    "DIR of <category>/<name>.{obj,off,ply,dae,stl,glb}, scene SPECs (.world, ScanNet scan, ...: "
                    "their categorised objects), 'procedural', 'sweethome3d' (Sweet Home 3D catalogs of "
                    "$OBJSCAN_SWEETHOME3D_DIR or /usr/share/sweethome3d/furniture) or a catalog X.sh3f")
      ->required();
  AddModelPathOption(build, &args->model_path, " (of --models worlds)");
  build->add_option("--category-map", args->category_map,
                    "category map YAML for --models worlds, scans and Sweet Home 3D catalogs (these default to "
                    "categories/sweethome3d.yaml)");
  build->add_option("--out", args->out, "output database file F.db")->required();
  build->add_option("--variants", args->variants, "procedural models per category")->default_str("8");
  build->add_option("--sampling", args->sampling,
                    "procedural models per category: 'styles' (every style of the generator in turn), 'style-medoids' (as styles, each style's size medoids), 'spread' (k-medoids over sizes) or 'first-seeds'")
      ->default_str("style-medoids");
  build->add_option("--threads", args->threads, "models scanned in parallel (0 = all cores; same result)")
      ->default_str("0");
  build->add_option("--seed", args->seed, "seed of the vocabulary (and of scan noise when on)")->default_str("1");
  build->add_option("--set", args->sets, "override a build option, e.g. descriptor.support_radius_m=0.12");
  auto* info = cmd->add_subcommand("info", "Print counts of models, components and pairs per category as JSON");
  info->add_option("db", args->info_db, "database file")->required();
  auto* eval = cmd->add_subcommand("eval", "Evaluate retrieval accuracy and objectness on unseen models");
  eval->add_option("--db", args->eval_db,
                   "database file, or 'default': the built-in one `objscan run` uses for the queries' scenes "
                   "(procedural for --queries procedural, the real Sweet Home 3D library otherwise)")
      ->required();
  eval->add_option("--queries", args->queries,
                   "query models, as --models of build: 'procedural' (unseen generator models), a DIR of "
                   "<category>/<name>.<ext>, scene SPECs (.world, ...: their categorised objects), 'sweethome3d' "
                   "or a catalog X.sh3f")
      ->default_str("procedural");
  eval->add_option("--queries-per-category", args->queries_per_category,
                   "query models per category (the first ones; 0 = all)")
      ->default_str("5");
  eval->add_option("--draws", args->draws,
                   "scans of each query model from new random views, for each kind of query (more draws: less "
                   "noise from the views; draw 1 is the same at any count)")
      ->default_str("1");
  AddModelPathOption(eval, &args->model_path, " (of --queries worlds)");
  eval->add_option("--category-map", args->category_map, "category map YAML for --queries worlds and scans");
  eval->add_option("--threads", args->threads, "queries run in parallel (0 = all cores)")->default_str("0");
  eval->add_option("--set", args->sets, "override an eval option, e.g. recognition.shortlist_size=30");
  cmd->require_subcommand(1);
  build->callback([run, args] { *run = [args] { return RunBuild(*args); }; });
  info->callback([run, args] { *run = [args] { return RunInfo(*args); }; });
  eval->callback([run, args] { *run = [args] { return RunEval(*args); }; });
}

}  // namespace objscan::app
