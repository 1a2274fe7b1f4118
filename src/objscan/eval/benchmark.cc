#include "objscan/eval/benchmark.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "objscan/common/error.h"
#include "objscan/io/atomic_file.h"
#include "objscan/scanning/system_config.h"

extern char** environ;

namespace objscan::eval {
namespace fs = std::filesystem;

const std::vector<std::string>& SceneCategories() {
  static const std::vector<std::string> kCategories = {"bedroom", "living_room", "kitchen", "bathroom", "office"};
  return kCategories;
}

std::string SceneCategoryOfSpec(const std::string& spec) {
  const auto& categories = SceneCategories();
  auto is_category = [&](const std::string& s) {
    return std::find(categories.begin(), categories.end(), s) != categories.end();
  };
  const std::string prefix = "procedural:";
  if (spec.rfind(prefix, 0) == 0) {
    const std::string rest = spec.substr(prefix.size());
    const std::string category = rest.substr(0, rest.find(':'));
    return is_category(category) ? category : "other";
  }
  for (const auto& part : fs::path(spec)) {
    if (is_category(part.string())) return part.string();
    if (is_category(part.stem().string())) return part.stem().string();
  }
  return "other";
}

namespace {

std::string SanitizeId(std::string s) {
  for (char& c : s) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    if (!ok) c = '-';
  }
  return s;
}

Suite WorldFolderSuite(const std::string& name, const fs::path& root) {
  std::error_code ec;
  if (!fs::is_directory(root, ec)) throw InputError(root.string() + ": suite folder not found");
  Suite suite;
  suite.name = name;
  for (auto it = fs::recursive_directory_iterator(root, fs::directory_options::follow_directory_symlink, ec);
       it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    if (!it->is_regular_file() || it->path().extension() != ".world") continue;
    const fs::path rel = fs::relative(it->path(), root);
    // The folders of the world, plus its stem unless it is the usual room.world.
    std::string id;
    for (const auto& part : rel.parent_path()) id += (id.empty() ? "" : "-") + part.string();
    if (it->path().stem() != "room" || id.empty()) id += (id.empty() ? "" : "-") + it->path().stem().string();
    BenchScene scene;
    scene.id = SanitizeId(id);
    scene.spec = fs::absolute(it->path()).lexically_normal().string();
    scene.category = SceneCategoryOfSpec(rel.string());
    suite.scenes.push_back(scene);
  }
  if (ec) throw InputError(root.string() + ": cannot list the suite folder: " + ec.message());
  if (suite.scenes.empty()) throw InputError(root.string() + ": no .world file in the suite folder");
  std::sort(suite.scenes.begin(), suite.scenes.end(),
            [](const BenchScene& a, const BenchScene& b) { return a.id < b.id; });
  for (std::size_t i = 1; i < suite.scenes.size(); ++i) {
    if (suite.scenes[i].id == suite.scenes[i - 1].id) {
      throw InputError(suite.scenes[i].spec + ": two worlds map to the same scene id " + suite.scenes[i].id);
    }
  }
  return suite;
}

}  // namespace

Suite ResolveSuite(const std::string& name_or_dir, const SuiteOptions& options) {
  options.Validate();
  if (name_or_dir == "procedural") {
    Suite suite;
    suite.name = "procedural";
    for (const auto& category : SceneCategories()) {
      // 64-bit: a first seed near INT_MAX must not overflow.
      const std::int64_t end = static_cast<std::int64_t>(options.first_seed) + options.seeds_per_category;
      for (std::int64_t seed = options.first_seed; seed < end; ++seed) {
        suite.scenes.push_back({"procedural-" + category + "-" + std::to_string(seed),
                                "procedural:" + category + ":" + std::to_string(seed), category});
      }
    }
    std::sort(suite.scenes.begin(), suite.scenes.end(),
              [](const BenchScene& a, const BenchScene& b) { return a.id < b.id; });
    return suite;
  }
  if (name_or_dir == "oasc-dev") {
    if (options.shared_data_dir.empty()) throw InputError("--suite oasc-dev: the shared data folder is not known");
    const fs::path root = fs::path(options.shared_data_dir) / "oasc-dev";
    if (!fs::is_directory(root)) {
      throw InputError(root.string() + ": the oasc-dev suite folder is missing (set $OBJSCAN_SHARED_DATA)");
    }
    Suite suite = WorldFolderSuite("oasc-dev", root);
    const fs::path models = fs::path(options.shared_data_dir) / "gazebo-models";
    if (fs::is_directory(models)) suite.model_path = fs::absolute(models).lexically_normal().string();
    return suite;
  }
  std::error_code ec;
  if (!fs::is_directory(name_or_dir, ec)) {
    throw InputError("--suite '" + name_or_dir + "': neither procedural, oasc-dev nor a folder");
  }
  return WorldFolderSuite(fs::path(name_or_dir).filename().string(), name_or_dir);
}

std::vector<BenchMethod> AllBenchMethods() {
  return {
      {"ours", "objscan's default: the paper's method with objscan's additions (config/default.yaml)", {}, false, ""},
      {"paper", "the paper's method as published (config/paper.yaml)", {}, false, "paper.yaml"},
      {"no-objectness", "NBO without the objectness term", {"nbo.objectness_weight=0"}, false, ""},
      {"no-size", "NBO without the size term", {"nbo.size_weight=0"}, false, ""},
      {"no-distance", "NBO without the distance term", {"nbo.distance_weight=0"}, false, ""},
      {"no-orientation", "NBO without the orientation term", {"nbo.orientation_weight=0"}, false, ""},
      {"frontier", "frontier exploration without object guidance (same step budget)", {"scanner.guidance=frontier"},
       false, ""},
      {"preseg-only", "recognition on pre-segmented components, no graph cuts (Tateno)",
       {"postsegmentation.graph_cuts=false"}, false, ""},
      {"db-no-parts", "database without component and pair entries (Fig. 14)", {}, true, ""},
  };
}

std::vector<BenchMethod> SelectBenchMethods(const std::string& comma_separated) {
  std::vector<BenchMethod> all = AllBenchMethods();
  if (comma_separated.empty() || comma_separated == "all") return all;
  std::set<std::string> wanted;
  std::stringstream in(comma_separated);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (name.empty()) continue;
    const bool known =
        std::any_of(all.begin(), all.end(), [&](const BenchMethod& m) { return m.name == name; });
    if (!known) {
      std::string names;
      for (const auto& m : all) names += (names.empty() ? "" : ", ") + m.name;
      throw InputError("--methods: unknown method '" + name + "' (known: " + names + ")");
    }
    wanted.insert(name);
  }
  if (wanted.empty()) throw InputError("--methods: no method given");
  std::vector<BenchMethod> out;
  for (auto& m : all) {
    if (wanted.count(m.name)) out.push_back(std::move(m));
  }
  return out;
}

Shard ParseShard(const std::string& text) {
  const auto slash = text.find('/');
  Shard shard;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    std::size_t used = 0;
    shard.index = std::stoi(text.substr(0, slash), &used);
    if (used != slash) throw std::invalid_argument("index");
    const std::string n = text.substr(slash + 1);
    shard.count = std::stoi(n, &used);
    if (used != n.size()) throw std::invalid_argument("count");
  } catch (const std::exception&) {
    throw InputError("--shard '" + text + "': expected i/n, e.g. 1/4");
  }
  if (shard.count < 1 || shard.index < 1 || shard.index > shard.count) {
    throw InputError("--shard '" + text + "': need 1 <= i <= n");
  }
  return shard;
}

std::vector<BenchJob> MakeJobs(const std::vector<BenchScene>& scenes, const std::vector<BenchMethod>& methods,
                               const std::string& out_dir) {
  std::vector<BenchJob> jobs;
  for (const auto& scene : scenes) {
    for (const auto& method : methods) {
      jobs.push_back({scene, method, (fs::path(out_dir) / "runs" / scene.id / method.name).string()});
    }
  }
  std::sort(jobs.begin(), jobs.end(), [](const BenchJob& a, const BenchJob& b) {
    return std::tie(a.scene.id, a.method.name) < std::tie(b.scene.id, b.method.name);
  });
  return jobs;
}

std::vector<BenchJob> ShardJobs(const std::vector<BenchJob>& jobs, const Shard& shard) {
  std::vector<BenchJob> out;
  for (std::size_t p = 0; p < jobs.size(); ++p) {
    if (static_cast<int>(p % shard.count) == shard.index - 1) out.push_back(jobs[p]);
  }
  return out;
}

bool IsCompleteRun(const std::string& run_dir) {
  std::ifstream in(fs::path(run_dir) / "run.json");
  if (!in) return false;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  return j.is_object() && j.contains("terminated") && j.contains("timing_s");
}

std::vector<BenchJob> PendingJobs(const std::vector<BenchJob>& jobs) {
  std::vector<BenchJob> out;
  for (const auto& job : jobs) {
    if (!IsCompleteRun(job.run_dir)) out.push_back(job);
  }
  return out;
}

std::vector<std::string> RunCommandArgs(const BenchJob& job, const RunCommandOptions& options) {
  std::vector<std::string> args = {"run",   "--scene", job.scene.spec,           "--out",
                                   job.run_dir, "--seed", std::to_string(options.seed), "--quiet"};
  if (!options.database.empty()) args.insert(args.end(), {"--db", options.database});
  if (!options.model_path.empty()) args.insert(args.end(), {"--model-path", options.model_path});
  if (!job.method.config_file.empty()) {
    args.insert(args.end(), {"--config", (fs::path(scanning::ConfigDir()) / job.method.config_file).string()});
  }
  for (const auto& s : options.sets) args.insert(args.end(), {"--set", s});
  for (const auto& s : job.method.config_sets) args.insert(args.end(), {"--set", s});
  return args;
}

namespace {

// Starts one child with stdout/stderr redirected into its folder; returns its pid or -1.
pid_t Spawn(const ChildCommand& command) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string out_path = (fs::path(command.dir) / "stdout.txt").string();
  const std::string err_path = (fs::path(command.dir) / "stderr.txt").string();
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char*> argv;
  for (const auto& a : command.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

void RecordOutcome(const ChildCommand& command, const ChildOutcome& outcome) {
  const fs::path failed = fs::path(command.dir) / "failed.json";
  std::error_code ec;
  if (outcome.ok) {
    fs::remove(failed, ec);
    return;
  }
  nlohmann::ordered_json j;
  for (const auto& [key, value] : command.labels) j[key] = value;
  j["exit_code"] = outcome.exit_code;
  j["seconds"] = outcome.seconds;
  j["stderr"] = "stderr.txt";
  std::string command_line;
  for (const auto& a : command.argv) command_line += (command_line.empty() ? "" : " ") + a;
  j["command"] = command_line;
  io::WriteFileAtomically(failed.string(), j.dump(2) + "\n");
}

}  // namespace

std::vector<ChildOutcome> RunChildProcesses(const std::vector<ChildCommand>& commands, int parallel,
                                            const ChildStartedFn& on_started, const ChildFinishedFn& on_finished) {
  using Clock = std::chrono::steady_clock;
  parallel = std::max(1, parallel);
  std::vector<ChildOutcome> outcomes(commands.size());
  std::map<pid_t, std::pair<std::size_t, Clock::time_point>> running;
  std::size_t next = 0;
  auto finish = [&](std::size_t index, int exit_code, Clock::time_point start) {
    ChildOutcome& o = outcomes[index];
    o.index = index;
    o.exit_code = exit_code;
    o.ok = exit_code == 0;
    o.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    RecordOutcome(commands[index], o);
    if (on_finished) on_finished(o);
  };
  while (next < commands.size() || !running.empty()) {
    while (next < commands.size() && static_cast<int>(running.size()) < parallel) {
      const std::size_t index = next++;
      std::error_code ec;
      fs::create_directories(commands[index].dir, ec);
      if (ec) throw InputError(commands[index].dir + ": cannot create the run folder: " + ec.message());
      if (on_started) on_started(index);
      const auto start = Clock::now();
      const pid_t pid = Spawn(commands[index]);
      if (pid < 0) {
        finish(index, 127, start);
        continue;
      }
      running[pid] = {index, start};
    }
    if (running.empty()) continue;
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;  // no children left (should not happen while `running` is not empty)
    }
    auto it = running.find(pid);
    if (it == running.end()) continue;  // not ours
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? -WTERMSIG(status) : 1;
    const auto [index, start] = it->second;
    running.erase(it);
    finish(index, code, start);
  }
  return outcomes;
}

recognition::ModelDatabase DatabaseWithoutParts(const recognition::ModelDatabase& database) {
  recognition::ModelDatabase out;
  out.mutable_settings() = database.settings();
  out.set_vocabulary(database.vocabulary());
  out.mutable_models() = database.models();
  std::vector<int> new_index(database.entries().size(), -1);
  for (std::size_t i = 0; i < database.entries().size(); ++i) {
    const recognition::DatabaseEntry& e = database.entries()[i];
    if (e.kind != recognition::EntryKind::kFullModel) continue;
    new_index[i] = static_cast<int>(out.entries().size());
    out.mutable_entries().push_back(e);
  }
  for (recognition::DatabaseModel& m : out.mutable_models()) {
    m.full_entry = m.full_entry >= 0 && m.full_entry < static_cast<int>(new_index.size())
                       ? new_index[static_cast<std::size_t>(m.full_entry)]
                       : -1;
  }
  out.Finalize();
  return out;
}

std::vector<recognition::ModelSource> ModelDisjointSources(const std::vector<WorldModels>& worlds,
                                                           std::size_t test_index) {
  std::set<std::string> excluded;
  if (test_index < worlds.size()) {
    for (const auto& o : worlds[test_index].scene.objects()) {
      if (!o.model_name.empty()) excluded.insert(o.model_name);
    }
  }
  // Every placement of a model in the other worlds: where it stands (the worlds' floors are at z = 0).
  std::map<std::string, std::vector<float>> support;
  for (std::size_t w = 0; w < worlds.size(); ++w) {
    if (w == test_index) continue;
    for (const auto& o : worlds[w].scene.objects()) {
      if (o.IsStructural() || o.model_name.empty() || o.mesh.triangles.empty()) continue;
      support[o.model_name].push_back(static_cast<float>(worlds[w].scene.ObjectBounds(o).min_m.z()));
    }
  }
  std::set<std::string> added;
  std::vector<recognition::ModelSource> sources;
  for (std::size_t w = 0; w < worlds.size(); ++w) {
    if (w == test_index) continue;
    const fs::path world_dir = fs::path(worlds[w].world_path).parent_path();
    for (const auto& o : worlds[w].scene.objects()) {
      if (o.IsStructural() || o.model_name.empty()) continue;
      if (excluded.count(o.model_name) || !added.insert(o.model_name).second) continue;
      if (o.mesh.triangles.empty()) continue;
      recognition::ModelSource s;
      s.category = o.category;
      s.name = std::string(world::CategoryName(o.category)) + "/" + o.model_name;
      s.source = worlds[w].world_path + "#" + o.name;
      for (const char* ext : {".dae", ".obj"}) {
        const fs::path mesh = world_dir / o.model_name / (o.model_name + ext);
        if (fs::exists(mesh)) {
          s.source = mesh.string();
          break;
        }
      }
      const geometry::TriangleMesh mesh = o.mesh;  // the object as the world places it (metres, Z up)
      s.load_mesh = [mesh] { return mesh; };
      s.support_heights_m = support[o.model_name];
      std::sort(s.support_heights_m.begin(), s.support_heights_m.end());
      sources.push_back(std::move(s));
    }
  }
  std::sort(sources.begin(), sources.end(),
            [](const recognition::ModelSource& a, const recognition::ModelSource& b) { return a.name < b.name; });
  return sources;
}

}  // namespace objscan::eval
