#include "run_scan.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <set>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "objscan/common/error.h"
#include "objscan/eval/frame_writer.h"
#include "objscan/eval/report_variants.h"
#include "objscan/eval/run_evaluation.h"
#include "objscan/eval/run_output.h"
#include "objscan/io/atomic_file.h"
#include "objscan/recognition/classifier_cache.h"
#include "objscan/recognition/database_cache.h"
#include "objscan/recognition/default_database.h"

namespace objscan::app {
namespace {

// What `objscan` says before a built-in database is built: a damaged cache always (it is not
// progress but something that went wrong), the build itself unless quiet.
std::function<void(const recognition::CachedDatabaseStatus&, const std::string&)> BuildNotice(bool verbose,
                                                                                              const char* what) {
  return [verbose, what](const recognition::CachedDatabaseStatus& status, const std::string& db_path) {
    if (!status.damage.empty()) {
      std::fprintf(stderr, "objscan: the cached model database is damaged, rebuilding it: %s\n", status.damage.c_str());
    } else if (verbose) {
      std::fprintf(stderr, "objscan: building %s (once; cached in %s)\n", what, db_path.c_str());
    }
  };
}

}  // namespace

std::string DefaultDatabasePath(bool verbose) {
  const std::string path = recognition::EnsureDefaultDatabase(
      recognition::DefaultDatabaseCacheDir(), TerminalProgress("database"),
      BuildNotice(verbose, "the procedural model database"));
  FinishProgress();
  return path;
}

std::string DefaultDatabasePathFor(const std::string& scene_spec, bool verbose) {
  if (recognition::UsesProceduralDatabase(scene_spec)) return DefaultDatabasePath(verbose);
  const std::string path = recognition::EnsureRealDatabase(
      recognition::DefaultDatabaseCacheDir(), TerminalProgress("database"),
      BuildNotice(verbose, "the real model database from the Sweet Home 3D library, a few minutes"));
  FinishProgress();
  return path;
}

std::vector<std::string> TrainingDatabasePaths(const std::vector<std::string>& names, bool verbose) {
  std::vector<std::string> paths = recognition::ResolveTrainingDatabases(
      names, recognition::DefaultDatabaseCacheDir(), TerminalProgress("database"),
      BuildNotice(verbose, "a built-in model database the category recognizer trains on"));
  FinishProgress();
  return paths;
}

void ReportClassifierCache(const recognition::CachedClassifierStatus& status) {
  for (const std::string& message : recognition::ClassifierCacheMessages(status)) {
    std::fprintf(stderr, "objscan: %s\n", message.c_str());
  }
}

namespace {

// The run's objects reported under each variant of the report options, scored like the run.
std::string ReportVariantsJson(const std::vector<eval::ReportVariant>& variants, const eval::RunEvaluator& evaluator,
                               const scanning::RunRecord& record, scanning::Scanner* scanner) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  scanning::RunRecord varied = record;
  for (const eval::ReportVariant& v : variants) {
    varied.objects = scanner->ReportWith(v.options);
    evaluator.AssignGroundTruthInstances(*scanner, &varied);
    const eval::RunMetrics m = evaluator.Evaluate(*scanner, varied);
    int labelled = 0;
    for (const auto& o : varied.objects) labelled += o.category.has_value();
    out[v.name] = {{"rules", v.options.rules},
                   {"recall", m.recall},
                   {"precision", m.precision},
                   {"coverage_rate", m.coverage_rate},
                   {"true_positives", m.true_positives},
                   {"output_objects", m.output_objects},
                   {"ground_truth_objects", m.ground_truth_objects},
                   {"labelled_objects", labelled}};
  }
  return out.dump(2) + "\n";
}

// Peak resident set size of this process so far (Linux reports ru_maxrss in KiB).
double PeakRssMb() {
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// CPU time of this process so far, user + system, all threads (-1 when unknown). Beside the wall
// time it shows how much of a run is parallel, and it is what a machine shared by several runs pays.
double CpuSeconds() {
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return -1.0;
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

}  // namespace

void AddConfigOptions(CLI::App* app, ConfigArgs* args) {
  app->add_option("--config", args->config_file, "YAML config file (see config/default.yaml)");
  app->add_option("--set", args->sets, "override a config key: section.key=value (repeatable)");
  AddModelPathOption(app, &args->model_path, " (sets scene.model_path)");
  app->add_flag("--doors-open", args->doors_open,
                "treat doors as open: remove every object of category door, for a scan of the whole house "
                "(sets scene.doors_open)");
  app->add_option("--category-map", args->category_map, "category map YAML (sets scene.category_map)");
}

scanning::SystemConfig LoadRunConfig(const ConfigArgs& args) {
  std::vector<std::string> sets = args.sets;
  if (!args.model_path.empty()) sets.push_back("scene.model_path=" + JoinModelPath(args.model_path));
  if (args.doors_open) sets.push_back("scene.doors_open=true");
  if (!args.category_map.empty()) sets.push_back("scene.category_map=" + args.category_map);
  return scanning::LoadSystemConfig(args.config_file, sets);
}

int ReportErrors(const char* program, const std::function<int()>& run) {
  try {
    return run();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return 1;
  }
}

RunDatabase LoadRunDatabase(const std::string& db_path, const std::string& scene_spec,
                            const scanning::SystemConfig& config, bool quiet) {
  RunDatabase db;
  db.path = db_path.empty() ? DefaultDatabasePathFor(scene_spec, !quiet) : db_path;
  db.database = recognition::ModelDatabase::Load(db.path,
                                                 DatabaseMemoryLimitBytes(config.recognition.max_database_memory_mb));
  if (db.database.models().empty()) throw InputError(db.path + ": the model database is empty");
  // The built-in databases the category recognizer also learns from, built now with progress rather
  // than silently when it is first asked (a database of generated models needs none of them).
  const auto& models = db.database.models();
  const bool generated = std::all_of(models.begin(), models.end(),
                                     [](const auto& m) { return m.source.rfind("procedural/", 0) == 0; });
  if (!generated) TrainingDatabasePaths(config.recognition.classifier.extra_training_databases, !quiet);
  return db;
}

int ScanAndWrite(const ScanRunInputs& in, platform::Platform* platform) {
  const scanning::SystemConfig& config = *in.config;
  const recognition::ModelDatabase& database = in.database->database;
  // Checked before anything is written.
  const std::vector<eval::ReportVariant> variants = eval::LoadReportVariants(config.eval.report_variants, config.report);
  std::set<world::Category> known;
  for (const auto& m : database.models()) known.insert(m.category);

  scanning::Scanner scanner(config, platform, database, in.seed);
  // Evaluation reads the scene's ground truth; without a scene the run has no metrics.
  std::unique_ptr<eval::RunEvaluator> evaluator;
  if (in.scene) {
    evaluator = std::make_unique<eval::RunEvaluator>(*in.scene, config,
                                                     std::vector<world::Category>(known.begin(), known.end()));
  }
  std::unique_ptr<eval::FrameWriter> frames;
  if (in.save_frames) frames = std::make_unique<eval::FrameWriter>(in.out + "/frames");
  scanner.set_frame_observer([&evaluator, &frames](const platform::DepthFrame& frame,
                                                   const mapping::FrameAssociation& association) {
    if (evaluator) evaluator->ObserveFrame(frame, association);
    if (frames) frames->Write(frame);
  });
  if (evaluator) {
    scanner.set_analysis_observer([&evaluator](const scanning::Scanner& s) { evaluator->ObserveAnalysis(s); });
  }
  const ProgressCallback bar = in.quiet ? nullptr : TerminalProgress("scanning");
  ProgressCallback progress = bar;
  if (in.on_step) {
    progress = [&in, &scanner, bar](double fraction, const std::string& what) {
      if (bar) bar(fraction, what);
      in.on_step(scanner, scanner.record(), false);
    };
  }
  scanning::RunRecord record = scanner.Run(progress);
  FinishProgress();
  ReportClassifierCache(scanner.classifier_cache_status());
  if (frames) frames->Finish(record);
  eval::RunMetrics metrics;
  if (evaluator) {
    evaluator->AssignGroundTruthInstances(scanner, &record);
    metrics = evaluator->Evaluate(scanner, record);
  }
  if (in.on_step) in.on_step(scanner, record, true);

  eval::RunOutputInputs outputs;
  outputs.record = &record;
  outputs.scanner = &scanner;
  outputs.database = &database;
  outputs.config = &config;
  outputs.metrics = evaluator ? &metrics : nullptr;
  outputs.scene_spec = in.scene_spec;
  outputs.database_path = in.database->path;
  if (!variants.empty() && evaluator) {
    const std::string variants_json = ReportVariantsJson(variants, *evaluator, record, &scanner);
    outputs.write_more_files = [variants_json](const std::string& out_dir) {
      io::WriteFileAtomically(out_dir + "/report_variants.json", variants_json);
    };
  }
  // Measured before the files are written (run.json holds them; writing them costs little of either).
  outputs.peak_rss_mb = PeakRssMb();
  outputs.cpu_s = CpuSeconds();
  // A placed model with no mesh is written as its scan points; say so once per model.
  const std::string program = in.program;
  outputs.warn = [program](const std::string& m) {
    std::fprintf(stderr, "%s: warning: %s\n", program.c_str(), m.c_str());
  };
  eval::WriteRunOutputs(in.out, outputs);

  // Rooms the robot could not enter (closed doors): the user is told, and given the metrics without
  // them. Rooms without objects (the floor outside a house's walls) are only listed in run.json.
  std::size_t rooms_with_objects = 0, objects = 0;
  double area_m2 = 0.0;
  for (const auto& u : metrics.unreachable_rooms) {
    if (u.objects.empty()) continue;
    ++rooms_with_objects;
    objects += u.objects.size();
    area_m2 += u.area_m2;
  }
  if (rooms_with_objects > 0) {
    std::fprintf(stderr,
                 "%s: note: %zu room%s (%.1f m2, %zu objects) could not be reached from the start (closed "
                 "doors?; --doors-open removes them); over the reachable rooms recall %.4f, precision %.4f "
                 "(run.json metrics.unreachable_rooms, metrics.reachable)\n",
                 program.c_str(), rooms_with_objects, rooms_with_objects == 1 ? "" : "s", area_m2, objects,
                 metrics.reachable.Recall(), metrics.reachable.Precision());
  }
  if (!metrics.never_seen.empty() && !in.quiet) {
    std::fprintf(stderr, "%s: note: %zu objects of the reachable rooms were never seen (run.json metrics.never_seen)\n",
                 program.c_str(), metrics.never_seen.size());
  }
  std::printf(
      "{\"out\": \"%s\", \"terminated\": \"%s\", \"views\": %d, \"objects\": %zu, \"recall\": %.4f, "
      "\"precision\": %.4f, \"coverage_rate\": %.4f, \"rand_index\": %.4f, \"travel_m\": %.2f, \"seconds\": %.2f, "
      "\"peak_rss_mb\": %.1f, \"cpu_s\": %.2f, \"unreachable_rooms\": %zu, \"recall_reachable\": %.4f, "
      "\"precision_reachable\": %.4f, \"unreachable_frontier_area_m2\": %.2f}\n",
      in.out.c_str(), scanning::TerminationName(record.terminated), record.views, record.objects.size(),
      metrics.recall, metrics.precision, metrics.coverage_rate, metrics.rand_index, record.travel_m,
      record.timing_s.total, outputs.peak_rss_mb, outputs.cpu_s, metrics.unreachable_rooms.size(),
      metrics.reachable.Recall(), metrics.reachable.Precision(), record.unreachable.frontier_area_m2);
  return 0;
}

}  // namespace objscan::app
