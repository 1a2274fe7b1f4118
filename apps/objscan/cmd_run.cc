// `objscan run`: scan a scene autonomously and write the DESIGN.md output folder.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "commands.h"
#include "objscan/common/config.h"
#include "objscan/common/error.h"
#include "objscan/eval/frame_writer.h"
#include "objscan/eval/report_variants.h"
#include "objscan/eval/run_evaluation.h"
#include "objscan/eval/run_output.h"
#include "objscan/io/atomic_file.h"
#include "objscan/io/scene_spec.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/recognition/database_cache.h"
#include "objscan/recognition/default_database.h"
#include "objscan/recognition/model_database.h"
#include "objscan/scanning/scanner.h"
#include "objscan/scanning/scene_limits.h"
#include "objscan/scanning/system_config.h"
#include "objscan/sim/simulated_robot.h"

namespace objscan::app {
namespace {

struct RunArgs {
  std::string scene = "procedural:bedroom:1";
  std::string db;
  std::string out = "objscan-out";
  std::uint64_t seed = 1;
  std::string config_file;
  std::vector<std::string> sets;
  std::vector<std::string> model_path;
  std::string category_map;
  bool doors_open = false;
  bool print_config = false;
  bool quiet = false;
  bool save_frames = false;
};

}  // namespace

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

int RunScan(const RunArgs& args) {
  std::vector<std::string> sets = args.sets;
  if (!args.model_path.empty()) sets.push_back("scene.model_path=" + JoinModelPath(args.model_path));
  if (args.doors_open) sets.push_back("scene.doors_open=true");
  if (!args.category_map.empty()) sets.push_back("scene.category_map=" + args.category_map);
  const scanning::SystemConfig config = scanning::LoadSystemConfig(args.config_file, sets);
  if (args.print_config) {
    std::fputs(scanning::ToYaml(config).c_str(), stdout);
    return 0;
  }
  // Check every input before writing anything.
  const std::vector<eval::ReportVariant> variants = eval::LoadReportVariants(config.eval.report_variants, config.report);
  const world::Scene scene = io::LoadScene(args.scene, config.scene);
  scanning::CheckSceneLimits(scene, config, args.scene);
  // What the loader changed or guessed (doors removed, instances inferred) bears on every metric.
  for (const std::string& note : scene.load_notes()) {
    if (!args.quiet) std::fprintf(stderr, "objscan run: note: %s\n", note.c_str());
  }
  const std::string db_path = args.db.empty() ? DefaultDatabasePathFor(args.scene, !args.quiet) : args.db;
  const recognition::ModelDatabase database = recognition::ModelDatabase::Load(
      db_path, DatabaseMemoryLimitBytes(config.recognition.max_database_memory_mb));
  if (database.models().empty()) throw InputError(db_path + ": the model database is empty");
  std::set<world::Category> known;
  for (const auto& m : database.models()) known.insert(m.category);
  // The built-in databases the category recognizer also learns from, built now with progress rather
  // than silently when it is first asked (a database of generated models needs none of them).
  const bool generated = std::all_of(database.models().begin(), database.models().end(),
                                     [](const auto& m) { return m.source.rfind("procedural/", 0) == 0; });
  if (!generated) TrainingDatabasePaths(config.recognition.classifier.extra_training_databases, !args.quiet);

  // The simulated robot, put down in the scene as an operator would; the scanner starts where it stands.
  sim::SimulatedRobot robot(scene, config.sensor, config.robot, config.navigation, args.seed);
  scanning::Scanner scanner(config, &robot, database, args.seed);
  eval::RunEvaluator evaluator(scene, config, std::vector<world::Category>(known.begin(), known.end()));
  std::unique_ptr<eval::FrameWriter> frames;
  if (args.save_frames) frames = std::make_unique<eval::FrameWriter>(args.out + "/frames");
  scanner.set_frame_observer([&evaluator, &frames](const platform::DepthFrame& frame,
                                                   const mapping::FrameAssociation& association) {
    evaluator.ObserveFrame(frame, association);
    if (frames) frames->Write(frame);
  });
  scanner.set_analysis_observer([&evaluator](const scanning::Scanner& s) { evaluator.ObserveAnalysis(s); });
  scanning::RunRecord record = scanner.Run(args.quiet ? nullptr : TerminalProgress("scanning"));
  FinishProgress();
  if (frames) frames->Finish(record);
  evaluator.AssignGroundTruthInstances(scanner, &record);
  const eval::RunMetrics metrics = evaluator.Evaluate(scanner, record);

  eval::RunOutputInputs outputs;
  outputs.record = &record;
  outputs.scanner = &scanner;
  outputs.database = &database;
  outputs.config = &config;
  outputs.metrics = &metrics;
  outputs.scene_spec = args.scene;
  outputs.database_path = db_path;
  if (!variants.empty()) {
    const std::string variants_json = ReportVariantsJson(variants, evaluator, record, &scanner);
    outputs.write_more_files = [variants_json](const std::string& out_dir) {
      io::WriteFileAtomically(out_dir + "/report_variants.json", variants_json);
    };
  }
  // Measured before the files are written (run.json holds them; writing them costs little of either).
  outputs.peak_rss_mb = PeakRssMb();
  outputs.cpu_s = CpuSeconds();
  // A placed model with no mesh is written as its scan points; say so once per model.
  outputs.warn = [](const std::string& m) { std::fprintf(stderr, "objscan run: warning: %s\n", m.c_str()); };
  eval::WriteRunOutputs(args.out, outputs);

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
                 "objscan run: note: %zu room%s (%.1f m2, %zu objects) could not be reached from the start (closed "
                 "doors?; --doors-open removes them); over the reachable rooms recall %.4f, precision %.4f "
                 "(run.json metrics.unreachable_rooms, metrics.reachable)\n",
                 rooms_with_objects, rooms_with_objects == 1 ? "" : "s", area_m2, objects,
                 metrics.reachable.Recall(), metrics.reachable.Precision());
  }
  if (!metrics.never_seen.empty() && !args.quiet) {
    std::fprintf(stderr,
                 "objscan run: note: %zu objects of the reachable rooms were never seen (run.json metrics.never_seen)\n",
                 metrics.never_seen.size());
  }
  std::printf(
      "{\"out\": \"%s\", \"terminated\": \"%s\", \"views\": %d, \"objects\": %zu, \"recall\": %.4f, "
      "\"precision\": %.4f, \"coverage_rate\": %.4f, \"rand_index\": %.4f, \"travel_m\": %.2f, \"seconds\": %.2f, "
      "\"peak_rss_mb\": %.1f, \"cpu_s\": %.2f, \"unreachable_rooms\": %zu, \"recall_reachable\": %.4f, "
      "\"precision_reachable\": %.4f, \"unreachable_frontier_area_m2\": %.2f}\n",
      args.out.c_str(), scanning::TerminationName(record.terminated), record.views, record.objects.size(),
      metrics.recall, metrics.precision, metrics.coverage_rate, metrics.rand_index, record.travel_m,
      record.timing_s.total, outputs.peak_rss_mb, outputs.cpu_s, metrics.unreachable_rooms.size(),
      metrics.reachable.Recall(), metrics.reachable.Precision(), record.unreachable.frontier_area_m2);
  return 0;
}

}  // namespace

void AddRunCommand(CLI::App& root, RunFn* run) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = root.add_subcommand("run", "Scan a scene autonomously (NBO + NBV) and write a labelled reconstruction");
  cmd->add_option("--scene", args->scene, "scene SPEC: .world, .yaml/.json scene file, ScanNet scan folder or *_vh_clean_2.ply, mesh, or procedural:CATEGORY:SEED")
      ->capture_default_str();
  cmd->add_option("--db", args->db, "model database file (default: the built-in procedural database for procedural scenes, the built-in real one, the Sweet Home 3D library, for every other scene; built once and cached)");
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--seed", args->seed, "random seed (sensor noise and every random choice)")->capture_default_str();
  cmd->add_option("--config", args->config_file, "YAML config file (see config/default.yaml)");
  cmd->add_option("--set", args->sets, "override a config key: section.key=value (repeatable)");
  AddModelPathOption(cmd, &args->model_path, " (sets scene.model_path)");
  cmd->add_flag("--doors-open", args->doors_open,
                "treat doors as open: remove every object of category door, for a scan of the whole house "
                "(sets scene.doors_open)");
  cmd->add_option("--category-map", args->category_map, "category map YAML (sets scene.category_map)");
  cmd->add_flag("--print-config", args->print_config, "print the effective configuration as YAML and exit");
  cmd->add_flag("--quiet", args->quiet, "no progress output on stderr");
  cmd->add_flag("--save-frames", args->save_frames,
                "also write every depth image to OUT/frames (TUM RGB-D layout: depth/NNNNNN.png at 5000 units "
                "per metre, depth.txt, groundtruth.txt camera poses, intrinsics.json)");
  cmd->callback([run, args] { *run = [args] { return RunScan(*args); }; });
}

}  // namespace objscan::app
