#pragma once
// The benchmark of `objscan bench` (paper §6, Results): a suite of scenes times a set of methods,
// each (scene, method) pair one `objscan run` in its own process and output folder
// OUT/runs/<scene-id>/<method>/. This file holds the pieces: suites, methods (the paper's method,
// its NBO ablations and the baselines as configuration overrides), the sorted job list and its
// shards, resumability, the parallel process runner, and the databases some methods need (a database
// without component and pair entries; model-disjoint databases from the other worlds of a suite).
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/common/progress.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/recognition/model_database.h"
#include "objscan/world/scene.h"

namespace objscan::eval {

// The paper's five scene categories (Table 1), in its order.
const std::vector<std::string>& SceneCategories();
// The scene category of a scene SPEC: CATEGORY of procedural:CATEGORY:SEED, else the first path
// component (or stem) naming a scene category; "other" when none does.
std::string SceneCategoryOfSpec(const std::string& spec);

struct BenchScene {
  std::string id;        // folder name under OUT/runs/, unique in the suite
  std::string spec;      // --scene of `objscan run`
  std::string category;  // scene category
};

struct SuiteOptions {
  int seeds_per_category = 2;   // procedural: scenes procedural:CATEGORY:F..F+N-1
  // F: 1 for the rooms the defaults were tuned on (seeds 1-3); 4 or more for rooms never tuned on.
  int first_seed = 1;
  std::string shared_data_dir;  // holds oasc-dev/ and gazebo-models/ (for the oasc-dev suite)

  template <class V>
  void Visit(V& v) {
    v("seeds_per_category", seeds_per_category);
    v("first_seed", first_seed);
    v("shared_data_dir", shared_data_dir);
  }
  void Validate() const {
    config::Require(seeds_per_category >= 1, "seeds_per_category", "must be >= 1");
    config::Require(first_seed >= 1, "first_seed", "must be >= 1");
  }
};

struct Suite {
  std::string name;
  std::vector<BenchScene> scenes;  // sorted by id
  std::string model_path;          // extra model:// folders the worlds need (empty for none)
};

// `procedural`, `oasc-dev`, or a folder searched recursively for .world files. Throws InputError
// naming the suite or folder when it is unknown, missing or holds no world.
Suite ResolveSuite(const std::string& name_or_dir, const SuiteOptions& options);

struct BenchMethod {
  std::string name;
  std::string description;
  std::vector<std::string> config_sets;  // key=value overrides of `objscan run`
  bool database_without_parts = false;   // uses the database variant without component/pair entries
  std::string config_file;               // a file of the config folder passed as --config ("" for none)
};

// Every method, in report order: ours, paper, no-objectness, no-size, no-distance, no-orientation,
// frontier, preseg-only, db-no-parts.
std::vector<BenchMethod> AllBenchMethods();
// A comma-separated list of method names (empty or "all": every method). Throws InputError naming
// an unknown method.
std::vector<BenchMethod> SelectBenchMethods(const std::string& comma_separated);

// --shard i/n: the i-th (1-based) of n slices.
struct Shard {
  int index = 1;
  int count = 1;
};
// Parses "i/n" with 1 <= i <= n; throws InputError naming --shard.
Shard ParseShard(const std::string& text);

struct BenchJob {
  BenchScene scene;
  BenchMethod method;
  std::string run_dir;  // OUT/runs/<scene-id>/<method>
};

// Every (scene, method) pair sorted by (scene id, method name): the order shards slice.
std::vector<BenchJob> MakeJobs(const std::vector<BenchScene>& scenes, const std::vector<BenchMethod>& methods,
                               const std::string& out_dir);
// The jobs of one shard: those at positions p of the sorted list with p % n == i - 1 (round robin,
// so every shard gets a mix of scenes and methods). The union over all shards is the whole list.
std::vector<BenchJob> ShardJobs(const std::vector<BenchJob>& jobs, const Shard& shard);

// True when `run_dir`/run.json exists and is a complete run (parses, carries "terminated" and
// "timing_s"). `objscan run` writes run.json last and atomically, so this marks a finished run.
bool IsCompleteRun(const std::string& run_dir);
// The jobs whose run is not complete yet (the rest are skipped on resume).
std::vector<BenchJob> PendingJobs(const std::vector<BenchJob>& jobs);

// The arguments (after the program name) of the `objscan run` of one job.
struct RunCommandOptions {
  std::string database;            // --db (empty: the run's default)
  std::string model_path;          // --model-path (empty: none)
  std::vector<std::string> sets;   // --set before the method's own (the method's win)
  std::uint64_t seed = 1;          // --seed
};
std::vector<std::string> RunCommandArgs(const BenchJob& job, const RunCommandOptions& options);

// Running child processes, `parallel` at a time. Each command runs with its stdout and stderr
// redirected to <dir>/stdout.txt and <dir>/stderr.txt (dir created). A command that exits non-zero
// or dies leaves <dir>/failed.json (exit code or signal, seconds) and does not stop the others; a
// command that succeeds removes a stale failed.json.
struct ChildCommand {
  std::vector<std::string> argv;  // argv[0] is the executable path
  std::string dir;
  std::vector<std::pair<std::string, std::string>> labels;  // copied into failed.json (e.g. scene, method)
};
struct ChildOutcome {
  std::size_t index = 0;  // into the command list
  bool ok = false;
  int exit_code = 0;      // -signal when killed by a signal; 127 when it could not start
  double seconds = 0.0;
};
using ChildStartedFn = std::function<void(std::size_t index)>;
using ChildFinishedFn = std::function<void(const ChildOutcome& outcome)>;
// Returns the outcomes in command order. Throws InputError when a folder cannot be created.
std::vector<ChildOutcome> RunChildProcesses(const std::vector<ChildCommand>& commands, int parallel,
                                            const ChildStartedFn& on_started = nullptr,
                                            const ChildFinishedFn& on_finished = nullptr);

// The variant of a database without component and pair entries (paper Fig. 14): the same models and
// full-model entries, vocabulary and description settings, with every component and pair entry left out
// (copied, not rebuilt: only the entries differ between the two databases).
recognition::ModelDatabase DatabaseWithoutParts(const recognition::ModelDatabase& database);

// Model-disjoint databases from worlds (OASC): the models of every world except `test_index`,
// leaving out every model id (SceneObject::model_name) that occurs in the test world, each id once,
// named "<category>/<id>". Structural objects and objects without a model id are left out; objects
// of category `other` (plants, towels, boxes) are kept, as the paper's database has an Other
// category: a query recognised as one of them is "none of the benchmark's categories", not a chair.
// Each source's support heights are the heights of the bottoms of all its placements in those
// worlds. `source` is the object's mesh file when one is found beside the world
// (<world dir>/<id>/<id>.{dae,obj}), else "<world file>#<object name>".
struct WorldModels {
  std::string world_path;
  world::Scene scene;
};
std::vector<recognition::ModelSource> ModelDisjointSources(const std::vector<WorldModels>& worlds,
                                                           std::size_t test_index);

}  // namespace objscan::eval
