#include "objscan/eval/benchmark.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "objscan/common/error.h"
#include "objscan/geometry/mesh.h"
#include "objscan/recognition/recognizer.h"
#include "objscan/recognition/test_database.h"

namespace objscan::eval {
namespace {
namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("objscan_bench_test_" + std::to_string(getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void WriteText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SceneCategoryTest, FromProceduralSpecAndPaths) {
  EXPECT_EQ(SceneCategoryOfSpec("procedural:living_room:3"), "living_room");
  EXPECT_EQ(SceneCategoryOfSpec("procedural:garage:3"), "other");
  EXPECT_EQ(SceneCategoryOfSpec("/data/oasc-dev/SUNCG/kitchen/abc/0_4/room.world"), "kitchen");
  EXPECT_EQ(SceneCategoryOfSpec("worlds/office.world"), "office");
  EXPECT_EQ(SceneCategoryOfSpec("worlds/room.world"), "other");
}

TEST(SuiteTest, ProceduralIsFiveCategoriesTimesSeeds) {
  SuiteOptions options;
  options.seeds_per_category = 3;
  const Suite suite = ResolveSuite("procedural", options);
  ASSERT_EQ(suite.scenes.size(), 15u);
  std::set<std::string> ids, specs;
  for (const auto& s : suite.scenes) {
    ids.insert(s.id);
    specs.insert(s.spec);
    EXPECT_EQ(SceneCategoryOfSpec(s.spec), s.category);
  }
  EXPECT_EQ(ids.size(), 15u);
  EXPECT_TRUE(specs.count("procedural:bathroom:1"));
  EXPECT_TRUE(specs.count("procedural:office:3"));
  EXPECT_FALSE(specs.count("procedural:office:4"));
  EXPECT_TRUE(std::is_sorted(suite.scenes.begin(), suite.scenes.end(),
                             [](const BenchScene& a, const BenchScene& b) { return a.id < b.id; }));
}

TEST(SuiteTest, ProceduralSeedsCanStartLater) {
  SuiteOptions options;
  options.seeds_per_category = 3;
  options.first_seed = 4;
  const Suite suite = ResolveSuite("procedural", options);
  ASSERT_EQ(suite.scenes.size(), 15u);
  std::set<std::string> specs;
  for (const auto& s : suite.scenes) specs.insert(s.spec);
  for (const char* category : {"bathroom", "bedroom", "kitchen", "living_room", "office"}) {
    for (int seed = 1; seed <= 7; ++seed) {
      const std::string spec = std::string("procedural:") + category + ":" + std::to_string(seed);
      EXPECT_EQ(specs.count(spec), seed >= 4 && seed <= 6 ? 1u : 0u) << spec;
    }
  }
  options.first_seed = 0;
  EXPECT_THROW(ResolveSuite("procedural", options), InputError);
}

TEST(SuiteTest, FolderIsSearchedRecursivelyForWorlds) {
  TempDir dir;
  WriteText(dir.path() / "SUNCG" / "bedroom" / "h1" / "0_7" / "room.world", "<sdf/>");
  WriteText(dir.path() / "SUNCG" / "kitchen" / "h2" / "0_4" / "room.world", "<sdf/>");
  WriteText(dir.path() / "extra" / "office.world", "<sdf/>");
  WriteText(dir.path() / "extra" / "notes.txt", "not a world");
  const Suite suite = ResolveSuite(dir.path().string(), SuiteOptions{});
  ASSERT_EQ(suite.scenes.size(), 3u);
  EXPECT_EQ(suite.scenes[0].id, "SUNCG-bedroom-h1-0_7");
  EXPECT_EQ(suite.scenes[0].category, "bedroom");
  EXPECT_EQ(suite.scenes[1].id, "SUNCG-kitchen-h2-0_4");
  EXPECT_EQ(suite.scenes[2].id, "extra-office");
  EXPECT_EQ(suite.scenes[2].category, "office");
  EXPECT_TRUE(fs::path(suite.scenes[0].spec).is_absolute());
}

TEST(SuiteTest, UnknownSuiteOrEmptyFolderThrows) {
  TempDir dir;
  EXPECT_THROW(ResolveSuite(dir.path().string(), SuiteOptions{}), InputError);
  EXPECT_THROW(ResolveSuite("no-such-suite", SuiteOptions{}), InputError);
  SuiteOptions missing;
  missing.shared_data_dir = (dir.path() / "nothing").string();
  EXPECT_THROW(ResolveSuite("oasc-dev", missing), InputError);
}

TEST(MethodsTest, AllAndSelection) {
  const auto all = AllBenchMethods();
  ASSERT_EQ(all.size(), 9u);
  EXPECT_EQ(all.front().name, "ours");
  EXPECT_TRUE(all.front().config_sets.empty());
  EXPECT_TRUE(all.front().config_file.empty());
  // The paper's method as published runs config/paper.yaml.
  const auto paper = SelectBenchMethods("paper");
  ASSERT_EQ(paper.size(), 1u);
  EXPECT_EQ(paper[0].config_file, "paper.yaml");
  const auto some = SelectBenchMethods("frontier,ours,no-size");
  ASSERT_EQ(some.size(), 3u);  // in report order, not in the order given
  EXPECT_EQ(some[0].name, "ours");
  EXPECT_EQ(some[1].name, "no-size");
  EXPECT_EQ(some[1].config_sets, std::vector<std::string>{"nbo.size_weight=0"});
  EXPECT_EQ(some[2].name, "frontier");
  EXPECT_EQ(SelectBenchMethods("").size(), 9u);
  EXPECT_TRUE(SelectBenchMethods("db-no-parts")[0].database_without_parts);
  EXPECT_THROW(SelectBenchMethods("ours,fastest"), InputError);
}

TEST(ShardTest, Parse) {
  const Shard s = ParseShard("2/5");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  for (const char* bad : {"0/3", "4/3", "1", "a/b", "1/0", "1/2x", ""}) {
    EXPECT_THROW(ParseShard(bad), InputError) << bad;
  }
}

TEST(JobsTest, SortedAndShardsPartitionTheList) {
  SuiteOptions options;
  options.seeds_per_category = 2;
  const Suite suite = ResolveSuite("procedural", options);
  const auto jobs = MakeJobs(suite.scenes, AllBenchMethods(), "/out");
  ASSERT_EQ(jobs.size(), 90u);
  for (std::size_t i = 1; i < jobs.size(); ++i) {
    EXPECT_LT(std::tie(jobs[i - 1].scene.id, jobs[i - 1].method.name), std::tie(jobs[i].scene.id, jobs[i].method.name));
  }
  EXPECT_EQ(jobs[0].run_dir, "/out/runs/" + jobs[0].scene.id + "/" + jobs[0].method.name);
  for (int n : {1, 3, 7, 90, 100}) {
    std::multiset<std::string> seen;
    std::size_t smallest = jobs.size(), largest = 0;
    for (int i = 1; i <= n; ++i) {
      const auto part = ShardJobs(jobs, {i, n});
      smallest = std::min(smallest, part.size());
      largest = std::max(largest, part.size());
      for (const auto& j : part) seen.insert(j.run_dir);
    }
    EXPECT_EQ(seen.size(), jobs.size()) << n;
    EXPECT_EQ(std::set<std::string>(seen.begin(), seen.end()).size(), jobs.size()) << n;  // disjoint
    EXPECT_LE(largest - smallest, 1u) << n;
  }
  // Shard 2/3 takes positions 1, 4, 7, ...
  const auto second = ShardJobs(jobs, {2, 3});
  EXPECT_EQ(second[0].run_dir, jobs[1].run_dir);
  EXPECT_EQ(second[1].run_dir, jobs[4].run_dir);
}

TEST(JobsTest, CompletedRunsAreSkipped) {
  TempDir dir;
  const std::vector<BenchScene> scenes = {{"s1", "procedural:bedroom:1", "bedroom"},
                                          {"s2", "procedural:office:1", "office"}};
  const auto jobs = MakeJobs(scenes, SelectBenchMethods("ours,frontier"), dir.path().string());
  ASSERT_EQ(jobs.size(), 4u);
  EXPECT_EQ(PendingJobs(jobs).size(), 4u);
  // Complete, truncated, and a run folder with only a failure record.
  WriteText(fs::path(jobs[0].run_dir) / "run.json", R"({"terminated": "done", "steps": [], "timing_s": {"total": 1}})");
  WriteText(fs::path(jobs[1].run_dir) / "run.json", R"({"terminated": "done", "steps": [)");
  WriteText(fs::path(jobs[2].run_dir) / "failed.json", R"({"exit_code": 1})");
  EXPECT_TRUE(IsCompleteRun(jobs[0].run_dir));
  EXPECT_FALSE(IsCompleteRun(jobs[1].run_dir));
  const auto pending = PendingJobs(jobs);
  ASSERT_EQ(pending.size(), 3u);
  for (const auto& p : pending) EXPECT_NE(p.run_dir, jobs[0].run_dir);
}

TEST(JobsTest, RunCommandArgs) {
  const BenchJob job{{"s1", "procedural:bedroom:2", "bedroom"}, SelectBenchMethods("no-size")[0], "/out/runs/s1/no-size"};
  RunCommandOptions options;
  options.database = "/db/x.db";
  options.sets = {"nbo.size_weight=3", "scanner.max_steps=5"};
  options.seed = 7;
  const auto args = RunCommandArgs(job, options);
  const std::vector<std::string> expected = {"run",    "--scene", "procedural:bedroom:2", "--out", "/out/runs/s1/no-size",
                                             "--seed", "7",       "--quiet",              "--db",  "/db/x.db",
                                             "--set",  "nbo.size_weight=3", "--set", "scanner.max_steps=5",
                                             "--set",  "nbo.size_weight=0"};
  EXPECT_EQ(args, expected);  // the method's own override comes last, so it wins
  // The paper method passes its config file of the config folder.
  const BenchJob paper{{"s1", "procedural:bedroom:2", "bedroom"}, SelectBenchMethods("paper")[0], "/out/runs/s1/paper"};
  const auto paper_args = RunCommandArgs(paper, RunCommandOptions());
  const auto config = std::find(paper_args.begin(), paper_args.end(), "--config");
  ASSERT_NE(config, paper_args.end());
  ASSERT_NE(config + 1, paper_args.end());
  EXPECT_EQ(std::filesystem::path(*(config + 1)).filename(), "paper.yaml");
  EXPECT_TRUE(std::filesystem::exists(*(config + 1))) << *(config + 1);
}

TEST(ChildProcessTest, RunsInParallelAndRecordsFailures) {
  TempDir dir;
  std::vector<ChildCommand> commands;
  for (int i = 0; i < 5; ++i) {
    ChildCommand c;
    c.dir = (dir.path() / ("job" + std::to_string(i))).string();
    const std::string script = i == 3 ? "echo broken >&2; exit 3" : "echo out" + std::to_string(i) + "; echo '{}' > done";
    c.argv = {"/bin/sh", "-c", "cd '" + c.dir + "' && " + script};
    c.labels = {{"method", "m" + std::to_string(i)}};
    commands.push_back(c);
  }
  // A stale failure record of an earlier attempt disappears when the command now succeeds.
  WriteText(fs::path(commands[0].dir) / "failed.json", "{}");
  int started = 0, finished = 0;
  const auto outcomes = RunChildProcesses(
      commands, 2, [&](std::size_t) { ++started; }, [&](const ChildOutcome&) { ++finished; });
  EXPECT_EQ(started, 5);
  EXPECT_EQ(finished, 5);
  ASSERT_EQ(outcomes.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(outcomes[i].index, static_cast<std::size_t>(i));
    EXPECT_EQ(outcomes[i].ok, i != 3) << i;
    const fs::path d = commands[i].dir;
    if (i == 3) {
      EXPECT_EQ(outcomes[i].exit_code, 3);
      EXPECT_EQ(ReadText(d / "stderr.txt"), "broken\n");
      const std::string failed = ReadText(d / "failed.json");
      EXPECT_NE(failed.find("\"exit_code\": 3"), std::string::npos) << failed;
      EXPECT_NE(failed.find("\"method\": \"m3\""), std::string::npos) << failed;
    } else {
      EXPECT_EQ(ReadText(d / "stdout.txt"), "out" + std::to_string(i) + "\n");
      EXPECT_TRUE(fs::exists(d / "done"));
      EXPECT_FALSE(fs::exists(d / "failed.json"));
    }
  }
}

TEST(ChildProcessTest, MissingExecutableIsAFailedRun) {
  TempDir dir;
  ChildCommand c;
  c.dir = (dir.path() / "job").string();
  c.argv = {(dir.path() / "no-such-program").string()};
  const auto outcomes = RunChildProcesses({c}, 1);
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_FALSE(outcomes[0].ok);
  EXPECT_TRUE(fs::exists(fs::path(c.dir) / "failed.json"));
}

world::SceneObject Object(const std::string& model, world::Category category) {
  world::SceneObject o;
  o.name = model + "_0";
  o.model_name = model;
  o.category = category;
  o.mesh = geometry::MakeBox(Eigen::Vector3d(0.5, 0.5, 0.5));
  return o;
}

// Fig. 14's variant: the same models and full-model entries (same descriptions), no part entries,
// and retrieval over full models answers as with the whole database.
TEST(WorldDatabaseTest, DatabaseWithoutPartsKeepsOnlyFullModels) {
  using namespace recognition;
  const ModelDatabase db = BuildDatabaseFromScans(testing::ShapeModels(0.01), testing::SmallDatabaseOptions());
  std::size_t parts = 0;
  for (const auto& e : db.entries()) parts += e.kind != EntryKind::kFullModel;
  ASSERT_GT(parts, 0u);
  const ModelDatabase no_parts = DatabaseWithoutParts(db);
  ASSERT_TRUE(no_parts.finalized());
  EXPECT_EQ(no_parts.entries().size(), db.entries().size() - parts);
  ASSERT_EQ(no_parts.models().size(), db.models().size());
  for (std::size_t m = 0; m < db.models().size(); ++m) {
    const int e = no_parts.models()[m].full_entry;
    ASSERT_GE(e, 0);
    EXPECT_EQ(no_parts.entries()[e].kind, EntryKind::kFullModel);
    EXPECT_EQ(no_parts.entries()[e].model_index, static_cast<int>(m));
    EXPECT_EQ(no_parts.entries()[e].keypoints, db.entries()[db.models()[m].full_entry].keypoints);
  }
  EXPECT_EQ(no_parts.vocabulary().num_words(), db.vocabulary().num_words());
  // A table seen whole: the same best full model from both databases.
  const Recognizer with(db, RecognitionOptions()), without(no_parts, RecognitionOptions());
  geometry::PointCloud table;
  testing::TableLike(0.012, &table.points, &table.normals);
  const auto a = with.Retrieve(with.Describe(table), RetrievalScope::kFullModels);
  const auto b = without.Retrieve(without.Describe(table), RetrievalScope::kAllEntries);
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  EXPECT_EQ(db.entries()[a[0].entry].model_index, no_parts.entries()[b[0].entry].model_index);
}

TEST(WorldDatabaseTest, ModelDisjointSources) {
  using world::Category;
  std::vector<WorldModels> worlds(3);
  worlds[0].world_path = "/w/a/room.world";
  worlds[0].scene.Add(Object("100", Category::kChair));
  worlds[0].scene.Add(Object("200", Category::kTable));
  worlds[1].world_path = "/w/b/room.world";
  worlds[1].scene.Add(Object("100", Category::kChair));  // in the test world: left out
  worlds[1].scene.Add(Object("300", Category::kBed));
  worlds[1].scene.Add(Object("400", Category::kOther));  // category other: kept
  worlds[1].scene.Add(Object("wall", Category::kWall));  // structural: left out
  worlds[2].world_path = "/w/c/room.world";
  world::SceneObject raised_bed = Object("300", Category::kBed);  // once only
  raised_bed.mesh = geometry::MakeBox(Eigen::Vector3d(0, 0, 0.4), Eigen::Vector3d(1, 1, 1));
  worlds[2].scene.Add(raised_bed);
  worlds[2].scene.Add(Object("500", Category::kSofa));
  const auto sources = ModelDisjointSources(worlds, 0);
  std::vector<std::string> names;
  for (const auto& s : sources) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"bed/300", "other/400", "sofa/500"}));
  EXPECT_EQ(sources[0].category, Category::kBed);
  EXPECT_EQ(sources[1].category, Category::kOther);
  // Support heights: the bottoms of every placement in the other worlds (boxes of Object() are
  // centred on the origin), ascending.
  EXPECT_EQ(sources[0].support_heights_m, (std::vector<float>{-0.25f, 0.4f}));
  EXPECT_EQ(sources[2].support_heights_m, (std::vector<float>{-0.25f}));
  EXPECT_EQ(sources[0].load_mesh().triangles.size(), 12u);
  // Test world 1 excludes 100, 300 and 400: the rest of worlds 0 and 2.
  names.clear();
  for (const auto& s : ModelDisjointSources(worlds, 1)) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"sofa/500", "table/200"}));
}

}  // namespace
}  // namespace objscan::eval
