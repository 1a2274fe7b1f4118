// `objscan bench`: run a benchmark suite of scenes x methods (each one `objscan run` in its own
// process, --jobs at a time, resumable, shardable) and write the report (see `objscan report`).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli_util.h"
#include "commands.h"
#include "objscan/common/error.h"
#include "objscan/eval/benchmark.h"
#include "objscan/eval/report.h"
#include "objscan/io/atomic_file.h"
#include "objscan/io/scene_spec.h"
#include "objscan/recognition/category_classifier.h"
#include "objscan/recognition/database_cache.h"
#include "objscan/recognition/model_database.h"
#include "objscan/scanning/system_config.h"

namespace objscan::app {

namespace {
namespace fs = std::filesystem;

struct BenchArgs {
  std::string suite;
  std::string db;
  std::string out = "objscan-bench";
  int jobs = 0;
  std::string methods;
  std::string shard = "1/1";
  int seeds = 2;
  int first_seed = 1;
  std::vector<std::string> sets;
  std::vector<std::string> model_path;
  std::string category_map;
  bool db_from_worlds = false;
  std::uint64_t seed = 1;
};

// ../shared/data beside the project ($OBJSCAN_SHARED_DATA wins); the project root is the parent of
// the config folder, else the working directory.
std::string SharedDataDir() {
  if (const char* d = std::getenv("OBJSCAN_SHARED_DATA")) return d;
  const fs::path from_config = fs::path(scanning::ConfigDir()).parent_path().parent_path() / "shared" / "data";
  if (fs::is_directory(from_config)) return from_config.lexically_normal().string();
  return fs::absolute("../shared/data").lexically_normal().string();
}

std::string SelfExecutable() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("/proc/self/exe") : p.string();
}

std::string Duration(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) {
    std::snprintf(buf, sizeof(buf), "%ldh%02ldm", s / 3600, (s / 60) % 60);
  } else {
    std::snprintf(buf, sizeof(buf), "%ldm%02lds", s / 60, s % 60);
  }
  return buf;
}

std::string JoinPaths(const std::string& a, const std::string& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return a + ":" + b;
}

// True when `path` holds a database whose checksum verifies.
bool ValidDatabase(const std::string& path) {
  try {
    recognition::ModelDatabase::Verify(path);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

// Builds `path` with `build` unless it holds a valid database (a killed build leaves nothing under the
// name, as Save is atomic; a damaged file is rebuilt: database_cache.h).
template <class BuildFn>
void EnsureDatabase(const std::string& path, const std::string& what, BuildFn build) {
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  if (ec) throw InputError(fs::path(path).parent_path().string() + ": cannot create: " + ec.message());
  io::RemoveStaleTempFiles(fs::path(path).parent_path().string());
  const auto start = std::chrono::steady_clock::now();
  std::size_t models = 0, entries = 0;
  const recognition::CachedDatabaseStatus status = recognition::EnsureCachedDatabase(
      path,
      [&] {
        recognition::ModelDatabase db = build();
        FinishProgress();
        models = db.models().size();
        entries = db.entries().size();
        return db;
      },
      [&](const recognition::CachedDatabaseStatus& s) {
        if (!s.damage.empty()) {
          std::fprintf(stderr, "objscan bench: the database is damaged, rebuilding %s: %s\n", what.c_str(), s.damage.c_str());
        } else {
          std::fprintf(stderr, "objscan bench: building %s -> %s\n", what.c_str(), path.c_str());
        }
      });
  if (!status.built) return;
  std::fprintf(stderr, "objscan bench: %zu models, %zu entries in %s\n", models, entries,
               Duration(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()).c_str());
}

int RunBench(const BenchArgs& a) {
  using Clock = std::chrono::steady_clock;
  const auto bench_start = Clock::now();
  eval::SuiteOptions suite_options;
  suite_options.seeds_per_category = a.seeds;
  suite_options.first_seed = a.first_seed;
  suite_options.shared_data_dir = SharedDataDir();
  if (a.seeds < 1) throw InputError("--seeds must be at least 1");
  if (a.first_seed < 1) throw InputError("--first-seed must be at least 1");
  const eval::Suite suite = eval::ResolveSuite(a.suite, suite_options);
  const std::vector<eval::BenchMethod> methods = eval::SelectBenchMethods(a.methods);
  const eval::Shard shard = eval::ParseShard(a.shard);
  if (a.db_from_worlds && suite.name == "procedural") {
    throw InputError("--db-from-worlds needs a suite of .world files (e.g. oasc-dev), not procedural");
  }
  if (a.db_from_worlds && !a.db.empty()) throw InputError("--db and --db-from-worlds exclude each other");
  const std::string model_path = JoinPaths(JoinModelPath(a.model_path), suite.model_path);
  // The configuration must be valid before any run starts (each run checks it again).
  std::vector<std::string> run_sets = a.sets;
  if (!a.category_map.empty()) {
    // The runs work in their own folders: a map given relative to here is passed on absolute.
    const std::string map = fs::exists(a.category_map) ? fs::absolute(a.category_map).string() : a.category_map;
    run_sets.push_back("scene.category_map=" + map);
  }
  std::vector<std::string> check_sets = run_sets;
  if (!model_path.empty()) check_sets.push_back("scene.model_path=" + model_path);
  const scanning::SystemConfig config = scanning::LoadSystemConfig("", check_sets);
  const std::uint64_t database_memory = DatabaseMemoryLimitBytes(config.recognition.max_database_memory_mb);
  // A damaged or too large --db fails here, in one line, not in every run.
  if (!a.db.empty()) recognition::ModelDatabase::Verify(a.db, database_memory);

  const std::string out = fs::absolute(a.out).lexically_normal().string();
  const std::vector<eval::BenchJob> jobs = eval::ShardJobs(eval::MakeJobs(suite.scenes, methods, out), shard);
  std::vector<eval::BenchJob> pending = eval::PendingJobs(jobs);
  // The short frontier runs last, so the parallel runs end together instead of one long run alone.
  std::stable_partition(pending.begin(), pending.end(),
                        [](const eval::BenchJob& job) { return job.method.name != "frontier"; });
  std::fprintf(stderr, "objscan bench: suite %s, %zu scenes x %zu methods; shard %d/%d: %zu runs, %zu done, %zu to run\n",
               suite.name.c_str(), suite.scenes.size(), methods.size(), shard.index, shard.count, jobs.size(),
               jobs.size() - pending.size(), pending.size());

  // Databases of the pending runs.
  std::map<std::string, std::string> database_of_run;  // run_dir -> --db
  const fs::path db_dir = fs::path(out) / "db";
  if (a.db_from_worlds) {
    std::set<std::string> need;  // database files to build
    for (const auto& job : pending) {
      const std::string path = (db_dir / "worlds" / (job.scene.id + (job.method.database_without_parts ? "-no-parts" : "") + ".db")).string();
      database_of_run[job.run_dir] = path;
      if (!ValidDatabase(path)) need.insert(path);
    }
    if (!need.empty()) {
      std::fprintf(stderr, "objscan bench: loading %zu worlds for the model-disjoint databases\n", suite.scenes.size());
      std::vector<eval::WorldModels> worlds;
      for (const auto& scene : suite.scenes) worlds.push_back({scene.spec, io::LoadScene(scene.spec, config.scene)});
      for (std::size_t i = 0; i < suite.scenes.size(); ++i) {
        for (bool no_parts : {false, true}) {
          const std::string path =
              (db_dir / "worlds" / (suite.scenes[i].id + (no_parts ? "-no-parts" : "") + ".db")).string();
          if (!need.count(path)) continue;
          EnsureDatabase(path, "the model-disjoint database of " + suite.scenes[i].id, [&] {
            recognition::DatabaseBuildOptions options;
            options.include_components = !no_parts;
            options.include_pairs = !no_parts;
            const auto sources = eval::ModelDisjointSources(worlds, i);
            if (sources.empty()) throw InputError(suite.scenes[i].spec + ": no model left for a model-disjoint database");
            return recognition::BuildDatabase(sources, options, TerminalProgress("db " + suite.scenes[i].id));
          });
        }
      }
    }
  } else if (!pending.empty()) {
    const std::string base =
        !a.db.empty() ? a.db : suite.name == "procedural" ? DefaultDatabasePath(true) : DefaultDatabasePathFor("", true);
    // The built-in databases the category recognizer learns from, built once here rather than by two
    // runs at once.
    if (suite.name != "procedural") TrainingDatabasePaths(recognition::CategoryClassifierOptions().extra_training_databases, true);
    const std::string no_parts = (db_dir / "no-parts.db").string();
    // Checked (and built) once, not once per run: verifying reads the whole file.
    if (std::any_of(pending.begin(), pending.end(), [](const eval::BenchJob& job) { return job.method.database_without_parts; })) {
      EnsureDatabase(no_parts, "the database without component and pair entries", [&] {
        const recognition::ModelDatabase db = recognition::ModelDatabase::Load(base, database_memory);
        return eval::DatabaseWithoutParts(db);
      });
    }
    for (const auto& job : pending) database_of_run[job.run_dir] = job.method.database_without_parts ? no_parts : base;
  }

  // The runs.
  const std::string self = SelfExecutable();
  std::vector<eval::ChildCommand> commands;
  for (const auto& job : pending) {
    eval::RunCommandOptions options;
    options.database = database_of_run[job.run_dir];
    options.model_path = model_path;
    options.sets = run_sets;
    options.seed = a.seed;
    eval::ChildCommand c;
    c.argv = {self};
    for (auto& arg : eval::RunCommandArgs(job, options)) c.argv.push_back(std::move(arg));
    c.dir = job.run_dir;
    c.labels = {{"scene", job.scene.spec}, {"scene_id", job.scene.id}, {"method", job.method.name}};
    commands.push_back(std::move(c));
  }
  const int parallel = a.jobs > 0 ? a.jobs : std::max(1u, std::thread::hardware_concurrency());
  const auto runs_start = Clock::now();
  std::size_t finished = 0, failed = 0;
  const bool tty = isatty(STDERR_FILENO) != 0;
  auto outcomes = eval::RunChildProcesses(
      commands, parallel, nullptr, [&](const eval::ChildOutcome& o) {
        ++finished;
        if (!o.ok) ++failed;
        const double elapsed = std::chrono::duration<double>(Clock::now() - runs_start).count();
        const double eta = elapsed / finished * (commands.size() - finished);
        const auto& job = pending[o.index];
        const int width = 24, filled = static_cast<int>(width * finished / std::max<std::size_t>(1, commands.size()));
        std::string bar = "[" + std::string(filled, '#') + std::string(width - filled, '.') + "]";
        std::fprintf(stderr, "%s%s %zu/%zu %-6s %s/%s %.0fs; elapsed %s, eta %s%s%s", tty ? "\r\033[K" : "", bar.c_str(),
                     finished, commands.size(), o.ok ? "ok" : "FAILED", job.scene.id.c_str(), job.method.name.c_str(),
                     o.seconds, Duration(elapsed).c_str(), Duration(eta).c_str(),
                     failed ? (" (" + std::to_string(failed) + " failed)").c_str() : "", tty ? "" : "\n");
        if (!o.ok && tty) std::fputc('\n', stderr);
        std::fflush(stderr);
      });
  if (tty && !commands.empty()) std::fputc('\n', stderr);
  const double runs_seconds = std::chrono::duration<double>(Clock::now() - runs_start).count();

  // bench.json: what this (shard of the) bench ran.
  nlohmann::ordered_json info;
  info["suite"] = suite.name;
  info["scenes"] = suite.scenes.size();
  nlohmann::ordered_json method_names = nlohmann::ordered_json::array();
  for (const auto& m : methods) method_names.push_back(m.name);
  info["methods"] = method_names;
  info["sets"] = a.sets;
  info["db"] = a.db_from_worlds ? std::string("from-worlds") : (a.db.empty() ? std::string("default") : a.db);
  info["shard"] = a.shard;
  info["jobs"] = parallel;
  info["runs_in_shard"] = jobs.size();
  info["runs_started"] = commands.size();
  info["runs_failed"] = failed;
  info["runs_wall_s"] = runs_seconds;
  std::error_code ec;
  fs::create_directories(out, ec);
  io::RemoveStaleTempFiles(out);  // a bench.json writer that was killed
  const std::string info_name = shard.count > 1 ? "bench-shard-" + std::to_string(shard.index) + ".json" : "bench.json";
  io::WriteFileAtomically((fs::path(out) / info_name).string(), info.dump(2) + "\n");

  // The report over everything in OUT (other shards sharing OUT included).
  const eval::Report report = eval::BuildReport(eval::CollectRuns({out}));
  const std::string report_dir = (fs::path(out) / "report").string();
  eval::WriteReport(report, report_dir);
  const double total_seconds = std::chrono::duration<double>(Clock::now() - bench_start).count();
  nlohmann::ordered_json j;
  j["out"] = out;
  j["report"] = report_dir + "/results.md";
  j["runs_in_shard"] = jobs.size();
  j["runs_started"] = commands.size();
  j["runs_failed"] = failed;
  j["runs_complete_in_report"] = report.complete_runs;
  j["runs_failed_in_report"] = report.failed_runs;
  j["wall_s"] = total_seconds;
  // Where the reported objects go wrong, per method and overall (also in the report's results.json).
  if (!report.errors.empty()) j["reported_objects"] = nlohmann::ordered_json::parse(eval::ReportedObjectsJson(report));
  std::printf("%s\n", j.dump(2).c_str());
  return failed > 0 ? 1 : 0;
}

}  // namespace

void AddBenchCommand(CLI::App& root, RunFn* run) {
  auto args = std::make_shared<BenchArgs>();
  auto* cmd = root.add_subcommand("bench", "Run a benchmark suite of scenes x methods and write a report");
  cmd->footer(
      "Methods: ours (objscan's default), paper (config/paper.yaml: the method as published), no-objectness,\n"
      "no-size, no-distance, no-orientation (NBO ablations), frontier (no object\n"
      "guidance), preseg-only (no graph cuts), db-no-parts (database without component/pair entries).\n"
      "Runs go to OUT/runs/<scene>/<method>/ (finished runs are skipped on a re-run; a failed run keeps its\n"
      "stderr.txt and failed.json); the report to OUT/report/. Exit status 1 when a run failed.");
  cmd->add_option("--suite", args->suite, "suite NAME (procedural, oasc-dev) or a DIR searched for .world files")
      ->required();
  cmd->add_option("--db", args->db, "model database file (default: the built-in procedural database for the procedural suite, the built-in real one, the Sweet Home 3D library, for suites of worlds)");
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--jobs", args->jobs, "parallel runs (0 = number of cores)")->capture_default_str();
  cmd->add_option("--methods", args->methods, "comma-separated methods (default: all)");
  cmd->add_option("--shard", args->shard, "run only slice i of n (1-based) of the sorted (scene, method) list")
      ->capture_default_str();
  cmd->add_option("--seeds", args->seeds, "procedural suite: scenes per category")->capture_default_str();
  cmd->add_option("--first-seed", args->first_seed,
                  "procedural suite: seed of the first scene of each category (10 for rooms no tuning has "
                  "looked at)")
      ->capture_default_str();
  cmd->add_option("--set", args->sets, "override a config key of every run: key=value (repeatable)");
  AddModelPathOption(cmd, &args->model_path, "");
  cmd->add_option("--category-map", args->category_map, "category map YAML of every run (sets scene.category_map)");
  cmd->add_option("--seed", args->seed, "random seed of every run")->capture_default_str();
  cmd->add_flag("--db-from-worlds", args->db_from_worlds,
                "per test world, a database of the other worlds' models without any model id of the test world");
  cmd->callback([run, args] { *run = [args] { return RunBench(*args); }; });
}

}  // namespace objscan::app
