// End-to-end test of `objscan run`: a short scan of a procedural room with a small database writes
// every file of the output folder, its coverage.ply and the report's error classes agree with
// run.json's metrics, and the same seed gives the same run.json apart from timings.
#include <gtest/gtest.h>

#include "run_command.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "objscan/eval/report.h"
#include "objscan/io/ply.h"

namespace {

namespace fs = std::filesystem;

using Result = objscan::testing::CommandResult;

Result RunObjscan(const std::string& args) { return objscan::testing::RunCommand(OBJSCAN_BINARY, args); }

nlohmann::json ReadJson(const fs::path& path) { return nlohmann::json::parse(objscan::testing::ReadFile(path)); }

// run.json without what depends on the machine's speed (and memory use and CPU time, which vary with
// threads and load).
nlohmann::json WithoutTimings(nlohmann::json j) {
  j.erase("timing_s");
  j.erase("peak_rss_mb");
  j.erase("cpu_s");
  for (auto& step : j["steps"]) step.erase("timing_ms");
  return j;
}

// A fresh scratch folder `name` with small.db in it: one procedural model per category keeps the
// database build short. Empty on failure (the test then fails with the build's stderr).
std::string ScratchWithSmallDatabase(const std::string& name, fs::path* dir) {
  *dir = objscan::testing::ScratchPath(name);
  fs::create_directories(*dir);
  const std::string db = (*dir / "small.db").string();
  const Result build = RunObjscan("db build --models procedural --variants 1 --out " + db);
  EXPECT_EQ(build.exit_code, 0) << build.err;
  return build.exit_code == 0 ? db : std::string();
}

TEST(RunE2eTest, ShortScanWritesEveryOutputAndTheSameSeedGivesTheSameRunJson) {
  fs::path dir;
  const std::string db = ScratchWithSmallDatabase("objscan_run_e2e", &dir);
  ASSERT_FALSE(db.empty());

  const std::string common = "run --scene procedural:bathroom:1 --db " + db + " --seed 3 --set scanner.max_steps=8 --out ";
  const Result a = RunObjscan(common + (dir / "a").string());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const Result b = RunObjscan(common + (dir / "b").string());
  ASSERT_EQ(b.exit_code, 0) << b.err;

  for (const char* file : {"run.json", "scene.ply", "models.ply", "trajectory.csv", "topview.png", "coverage.ply"}) {
    EXPECT_TRUE(fs::exists(dir / "a" / file)) << file;
  }
  const nlohmann::json run = ReadJson(dir / "a" / "run.json");
  const std::string terminated = run["terminated"];
  EXPECT_TRUE(terminated == "done" || terminated == "max_steps") << terminated;
  EXPECT_LE(run["steps"].size(), 8u);
  EXPECT_GT(run["metrics"]["views"].get<int>(), 0);
  EXPECT_EQ(WithoutTimings(run), WithoutTimings(ReadJson(dir / "b" / "run.json")));

  // The report's error classes, rebuilt from run.json alone, agree with the run's own matching:
  // `correct` is precision's numerator, and every output falls in one class.
  const objscan::eval::RunSummary summary = objscan::eval::ParseRunJson(
      objscan::testing::ReadFile(dir / "a" / "run.json"), "a", "ours", (dir / "a" / "run.json").string());
  ASSERT_TRUE(summary.has_error_analysis);
  EXPECT_EQ(summary.errors.Count(objscan::eval::OutputOutcome::kCorrect), run["metrics"]["true_positives"].get<int>());
  EXPECT_EQ(summary.errors.Total(), run["metrics"]["output_objects"].get<int>());

  // coverage.ply holds V_S: as many voxels as the instances list, as many visible ones as the
  // visible rate says, and the covered ones (visible and detected) give the coverage rate.
  const objscan::io::PlyData coverage = objscan::io::ReadPly((dir / "a" / "coverage.ply").string());
  long surface = 0, visible_listed = 0;
  for (const auto& i : run["metrics"]["instances"]) {
    surface += i["surface_voxels"].get<long>();
    visible_listed += i["visible_voxels"].get<long>();
  }
  ASSERT_EQ(static_cast<long>(coverage.points.size()), surface);
  ASSERT_GT(surface, 0);
  const std::vector<std::int32_t>* visible = nullptr;
  const std::vector<std::int32_t>* detected = nullptr;
  const std::vector<std::int32_t>* reported = nullptr;
  const std::vector<std::int32_t>* observable = nullptr;
  for (const auto& [name, values] : coverage.int_properties) {
    if (name == "visible") visible = &values;
    if (name == "detected") detected = &values;
    if (name == "reported") reported = &values;
    if (name == "observable") observable = &values;
  }
  ASSERT_NE(visible, nullptr);
  ASSERT_NE(detected, nullptr);
  ASSERT_NE(reported, nullptr);
  ASSERT_NE(observable, nullptr);
  // By default V_S holds only observable voxels (eval/observability.h).
  EXPECT_EQ(std::count(observable->begin(), observable->end(), 0), 0);
  long num_visible = 0, num_covered = 0, num_covered_reported = 0;
  for (std::size_t v = 0; v < visible->size(); ++v) {
    num_visible += (*visible)[v];
    num_covered += (*visible)[v] && (*detected)[v];
    num_covered_reported += (*visible)[v] && (*reported)[v];
    // A matched instance is the majority instance of a reported object.
    EXPECT_TRUE(!(*detected)[v] || (*reported)[v]) << "voxel " << v;
  }
  const nlohmann::json& metrics = run["metrics"];
  EXPECT_EQ(num_visible, visible_listed);
  EXPECT_NEAR(static_cast<double>(num_visible) / surface, metrics["coverage_visible_rate"].get<double>(), 1e-9);
  EXPECT_NEAR(static_cast<double>(num_covered) / surface, metrics["coverage_rate"].get<double>(), 1e-9);
  EXPECT_NEAR(static_cast<double>(num_covered_reported) / surface, metrics["coverage_detected_rate"].get<double>(),
              1e-9);

  // Without eval.coverage_observable_only the same scan keeps the unobservable voxels in V_S,
  // flagged 0; the observable ones are the default's V_S, voxel for voxel.
  const Result c = RunObjscan(common + (dir / "c").string() + " --set eval.coverage_observable_only=false");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const objscan::io::PlyData all = objscan::io::ReadPly((dir / "c" / "coverage.ply").string());
  const std::vector<std::int32_t>* all_observable = nullptr;
  for (const auto& [name, values] : all.int_properties) {
    if (name == "observable") all_observable = &values;
  }
  ASSERT_NE(all_observable, nullptr);
  std::vector<std::array<float, 3>> kept, default_vs;
  for (std::size_t v = 0; v < all.points.size(); ++v) {
    if ((*all_observable)[v]) kept.push_back({all.points[v].x(), all.points[v].y(), all.points[v].z()});
  }
  for (const auto& p : coverage.points) default_vs.push_back({p.x(), p.y(), p.z()});
  EXPECT_GT(all.points.size(), kept.size());
  EXPECT_EQ(kept, default_vs);
  fs::remove_all(dir);
}

// Coverage views (scanning/coverage_views.h) come only once the paper's loop has nothing left: with
// them off the same room and seed end `done` at some step N; with them on, the first N steps are the
// same views, the coverage views follow (action nbv, coverage_view true, an object of interest), and
// what the camera saw only grows, so the visible share of V_S is at least as large. Here it must grow.
TEST(RunE2eTest, CoverageViewsFollowThePapersLoopAndAddToWhatWasSeen) {
  fs::path dir;
  const std::string db = ScratchWithSmallDatabase("objscan_run_e2e_coverage", &dir);
  ASSERT_FALSE(db.empty());
  const std::string common = "run --scene procedural:bathroom:1 --db " + db + " --seed 3 --out ";
  const Result off = RunObjscan(common + (dir / "off").string() + " --set scanner.coverage_views.enabled=false");
  ASSERT_EQ(off.exit_code, 0) << off.err;
  const Result on = RunObjscan(common + (dir / "on").string());
  ASSERT_EQ(on.exit_code, 0) << on.err;
  const nlohmann::json a = ReadJson(dir / "off" / "run.json");
  const nlohmann::json b = ReadJson(dir / "on" / "run.json");
  ASSERT_EQ(a["terminated"], "done");
  EXPECT_EQ(a["metrics"]["coverage_views"], 0);
  const std::size_t n = a["steps"].size();
  ASSERT_GT(b["steps"].size(), n);
  // The paper's loop: the same steps up to the one where the run without coverage views ended.
  for (std::size_t i = 0; i + 1 < n; ++i) {
    EXPECT_EQ(b["steps"][i]["pose"], a["steps"][i]["pose"]) << "step " << i;
    EXPECT_FALSE(b["steps"][i]["coverage_view"].get<bool>()) << "step " << i;
  }
  int coverage_steps = 0;
  for (const auto& step : b["steps"]) {
    if (!step["coverage_view"].get<bool>()) continue;
    ++coverage_steps;
    EXPECT_EQ(step["action"], "nbv");
    EXPECT_GE(step["ooi"].get<int>(), 0);
    EXPECT_EQ(step["nbv_candidates"].size(), 16u);
  }
  EXPECT_GT(coverage_steps, 0);
  EXPECT_EQ(b["metrics"]["coverage_views"].get<int>(), coverage_steps);
  EXPECT_GT(b["metrics"]["views"].get<int>(), a["metrics"]["views"].get<int>());
  EXPECT_GT(b["metrics"]["coverage_visible_rate"].get<double>(), a["metrics"]["coverage_visible_rate"].get<double>());
}

}  // namespace
