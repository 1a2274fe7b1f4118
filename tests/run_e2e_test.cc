// End-to-end test of `objscan run`: a short scan of a procedural room with a small database writes
// every file of the output folder, its coverage.ply and the report's error classes agree with
// run.json's metrics, and the same seed gives the same run.json apart from timings.
#include <gtest/gtest.h>

#include "run_command.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "objscan/eval/report.h"
#include "objscan/geometry/pose.h"
#include "objscan/io/ply.h"
#include "objscan/world/category.h"

namespace {

namespace fs = std::filesystem;

using Result = objscan::testing::CommandResult;

Result RunObjscan(const std::string& args) { return objscan::testing::RunCommand(OBJSCAN_BINARY, args); }

nlohmann::json ReadJson(const fs::path& path) { return nlohmann::json::parse(objscan::testing::ReadFile(path)); }

void WriteText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

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

  for (const char* file : {"run.json", "scene.ply", "models.ply", "trajectory.csv", "trajectory.tum", "categories.json",
                           "topview.png", "coverage.ply"}) {
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

const std::vector<std::int32_t>* IntProperty(const objscan::io::PlyData& ply, const std::string& name) {
  for (const auto& [n, values] : ply.int_properties) {
    if (n == name) return &values;
  }
  return nullptr;
}

// The lines of a text file that are not '#' comments.
std::vector<std::string> DataLines(const fs::path& path) {
  std::istringstream in(objscan::testing::ReadFile(path));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  }
  return lines;
}

// A run's PLY files open coloured by category in any viewer and name their classes: scene.ply and
// models.ply keep x y z (nx ny nz) object_id category_id and add red green blue from the palette of
// the top view legend, `label` (= category_id) and `instance` (= object_id); every point of a
// reported object carries that object's category from run.json; the header and categories.json name
// every id with the same colour. trajectory.tum has one line per view of trajectory.csv, at the
// camera positions and yaw/pitch written there, with unit quaternions; the last view of each step is
// run.json's step pose.
TEST(RunE2eTest, PlyFilesCarryCategoryColoursAndNamesAndTheTumTrajectoryHoldsTheViews) {
  namespace world = objscan::world;
  fs::path dir;
  const std::string db = ScratchWithSmallDatabase("objscan_run_e2e_viewers", &dir);
  ASSERT_FALSE(db.empty());
  const Result r = RunObjscan("run --scene procedural:bathroom:1 --db " + db +
                              " --seed 3 --set scanner.max_steps=8 --out " + (dir / "a").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path out = dir / "a";
  const nlohmann::json run = ReadJson(out / "run.json");

  // categories.json: -1 and every category, names and palette colours.
  const nlohmann::json categories = ReadJson(out / "categories.json");
  ASSERT_EQ(categories["categories"].size(), 1u + world::kNumCategories);
  std::map<int, std::string> comment_of_id;
  for (const auto& c : categories["categories"]) {
    const int id = c["id"];
    const auto rgb = world::LabelColor(id);
    EXPECT_EQ(c["color"], nlohmann::json({rgb[0], rgb[1], rgb[2]})) << id;
    EXPECT_EQ(c["name"], id < 0 ? std::string("unrecognized") : world::CategoryName(static_cast<world::Category>(id)));
    comment_of_id[id] = "category " + std::to_string(id) + " " + c["name"].get<std::string>() + " " +
                        std::to_string(rgb[0]) + " " + std::to_string(rgb[1]) + " " + std::to_string(rgb[2]);
  }

  std::map<int, int> category_of_object;  // reported objects with a category, from run.json
  int complete_objects = 0;
  for (const auto& o : run["objects"]) {
    if (!o["category"].is_null()) {
      category_of_object[o["id"]] = world::CategoryId(*world::ParseCategory(o["category"].get<std::string>()));
    }
    complete_objects += o["complete"].get<bool>() ? 1 : 0;
  }
  ASSERT_FALSE(category_of_object.empty());
  ASSERT_GT(complete_objects, 0);  // so models.ply has points to check

  for (const char* name : {"scene.ply", "models.ply"}) {
    SCOPED_TRACE(name);
    const objscan::io::PlyData ply = objscan::io::ReadPly((out / name).string());
    ASSERT_GT(ply.points.size(), 0u);
    ASSERT_EQ(ply.colors.size(), ply.points.size());
    std::vector<std::string> field_names;
    for (const auto& [n, values] : ply.int_properties) field_names.push_back(n);
    EXPECT_EQ(field_names, (std::vector<std::string>{"object_id", "category_id", "label", "instance"}));
    const auto* object_id = IntProperty(ply, "object_id");
    const auto* category_id = IntProperty(ply, "category_id");
    const auto* label = IntProperty(ply, "label");
    const auto* instance = IntProperty(ply, "instance");
    ASSERT_TRUE(object_id && category_id && label && instance);
    EXPECT_EQ(*label, *category_id);
    EXPECT_EQ(*instance, *object_id);
    std::map<int, long> points_per_label;
    std::set<int> complete_instances;
    for (std::size_t i = 0; i < ply.points.size(); ++i) {
      const int l = (*label)[i];
      const auto rgb = world::LabelColor(l);
      ASSERT_EQ(ply.colors[i], (std::array<std::uint8_t, 3>{rgb[0], rgb[1], rgb[2]})) << "point " << i;
      ++points_per_label[l];
      const auto it = category_of_object.find((*instance)[i]);
      if (it != category_of_object.end()) {
        ASSERT_EQ(l, it->second) << "point " << i << " of object " << (*instance)[i];
      }
      complete_instances.insert((*instance)[i]);
    }
    if (std::string(name) == "models.ply") {
      EXPECT_EQ(static_cast<int>(complete_instances.size()), complete_objects);
    } else {
      // The room's floor and walls and at least one object category, each in its own colour.
      EXPECT_GT(points_per_label[world::CategoryId(world::Category::kFloor)], 0);
      EXPECT_GT(points_per_label[world::CategoryId(world::Category::kWall)], 0);
      int object_labels = 0;
      for (const auto& [l, n] : points_per_label) {
        object_labels += l >= 0 && !world::IsStructural(static_cast<world::Category>(l)) ? 1 : 0;
      }
      EXPECT_GE(object_labels, 1);
    }
    // The header names every id as categories.json does.
    for (const auto& [id, comment] : comment_of_id) {
      EXPECT_NE(std::find(ply.comments.begin(), ply.comments.end(), comment), ply.comments.end()) << comment;
    }
  }
  // coverage.ply: its own colours and ground-truth instance, plus `label` (= category_id).
  const objscan::io::PlyData coverage = objscan::io::ReadPly((out / "coverage.ply").string());
  ASSERT_NE(IntProperty(coverage, "label"), nullptr);
  EXPECT_EQ(*IntProperty(coverage, "label"), *IntProperty(coverage, "category_id"));

  // trajectory.tum against trajectory.csv's views and run.json.
  const std::vector<std::string> tum = DataLines(out / "trajectory.tum");
  std::vector<std::vector<double>> csv_views;
  std::vector<int> csv_view_steps;
  for (const std::string& line : DataLines(out / "trajectory.csv")) {
    if (line.rfind("step,", 0) == 0) continue;  // the header
    std::vector<double> v;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 11u) << line;
    if (v[10] == 1.0) {
      csv_views.push_back(v);
      csv_view_steps.push_back(static_cast<int>(v[0]));
    }
  }
  ASSERT_EQ(tum.size(), run["metrics"]["views"].get<std::size_t>());
  ASSERT_EQ(tum.size(), csv_views.size());
  std::map<int, Eigen::Quaterniond> last_view_of_step;
  double previous_t = -1.0;
  for (std::size_t i = 0; i < tum.size(); ++i) {
    std::istringstream row(tum[i]);
    double t, x, y, z, qx, qy, qz, qw;
    ASSERT_TRUE(row >> t >> x >> y >> z >> qx >> qy >> qz >> qw) << tum[i];
    const std::vector<double>& c = csv_views[i];
    EXPECT_GE(t, previous_t) << "line " << i;
    previous_t = t;
    EXPECT_NEAR(t, c[1], 1e-4) << "line " << i;
    EXPECT_NEAR(x, c[5], 1e-4) << "line " << i;
    EXPECT_NEAR(y, c[6], 1e-4) << "line " << i;
    EXPECT_NEAR(z, c[7], 1e-4) << "line " << i;
    const Eigen::Quaterniond q(qw, qx, qy, qz);
    EXPECT_NEAR(q.norm(), 1.0, 1e-6) << "line " << i;
    objscan::geometry::Pose3 T = objscan::geometry::Pose3::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    double yaw = 0, pitch = 0;
    objscan::geometry::YawPitchOfCamera(T, &yaw, &pitch);
    EXPECT_NEAR(std::remainder(objscan::geometry::RadToDeg(yaw) - c[8], 360.0), 0.0, 1e-3) << "line " << i;
    EXPECT_NEAR(objscan::geometry::RadToDeg(pitch), c[9], 1e-3) << "line " << i;
    last_view_of_step[csv_view_steps[i]] = q;
  }
  for (const auto& step : run["steps"]) {
    const auto it = last_view_of_step.find(step["index"].get<int>());
    if (it == last_view_of_step.end()) continue;  // a step without a view
    const auto& w = step["pose"]["quat_wxyz"];
    const Eigen::Quaterniond q(w[0].get<double>(), w[1].get<double>(), w[2].get<double>(), w[3].get<double>());
    EXPECT_NEAR(std::abs(q.dot(it->second)), 1.0, 1e-6) << "step " << step["index"];
  }
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

// The step budget is min(max_steps, max(step_budget, steps_per_explored_m2 x explored area)): with
// a budget of one step and 0.2 steps per m2 the run gets as many steps as a fifth of the area it
// explored, and max_steps caps that whatever the area.
TEST(RunE2eTest, StepBudgetGrowsWithTheExploredAreaUpToMaxSteps) {
  fs::path dir;
  const std::string db = ScratchWithSmallDatabase("objscan_run_e2e_budget", &dir);
  ASSERT_FALSE(db.empty());
  const std::string common = "run --scene procedural:bedroom:2 --db " + db +
                             " --seed 5 --quiet --set scanner.step_budget=1 --set scanner.steps_per_explored_m2=0.2 ";

  const Result a = RunObjscan(common + "--set scanner.max_steps=40 --out " + (dir / "by_area").string());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const nlohmann::json run = ReadJson(dir / "by_area" / "run.json");
  const double area_m2 = run["explored_area_m2"].get<double>();
  const int budget = run["step_budget"].get<int>();
  EXPECT_GT(area_m2, 8.0) << "a procedural bedroom and what the look-around shows of it";
  EXPECT_LT(area_m2, 200.0);
  EXPECT_NEAR(budget, 0.2 * area_m2, 1.0);
  EXPECT_GE(budget, 2) << "more than step_budget: the area added steps";
  ASSERT_EQ(run["terminated"], "max_steps") << "a few steps do not finish a bedroom";
  EXPECT_EQ(static_cast<int>(run["steps"].size()), budget);

  const Result b = RunObjscan(common + "--set scanner.max_steps=2 --out " + (dir / "capped").string());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const nlohmann::json capped = ReadJson(dir / "capped" / "run.json");
  EXPECT_EQ(capped["step_budget"].get<int>(), 2);
  EXPECT_EQ(capped["steps"].size(), 2u);
  EXPECT_EQ(capped["terminated"], "max_steps");
}

TEST(RunE2eTest, UnreachableFrontiersEndTheRunDoneAndAreListed) {
  fs::path dir;
  const std::string db = ScratchWithSmallDatabase("objscan_run_e2e_unreachable", &dir);
  ASSERT_FALSE(db.empty());
  // Frontier exploration of this living room leaves two frontiers in the inflated margin beside
  // furniture (no path reaches them) while the robot can still drive: that is `done`, not `stuck`
  // (which objscan said before), and run.json says what was left.
  const Result r = RunObjscan("run --scene procedural:living_room:2 --db " + db +
                              " --set scanner.guidance=frontier --quiet --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json run = ReadJson(dir / "out" / "run.json");
  EXPECT_EQ(run["terminated"], "done");
  const nlohmann::json& unreachable = run["unreachable"];
  ASSERT_FALSE(unreachable["frontiers"].empty()) << unreachable.dump();
  double area_m2 = 0.0;
  for (const auto& f : unreachable["frontiers"]) {
    EXPECT_GE(f["cells"].get<int>(), 5);
    EXPECT_NEAR(f["area_m2"].get<double>(), 0.05 * 0.05 * f["cells"].get<int>(), 1e-4);
    area_m2 += f["area_m2"].get<double>();
  }
  EXPECT_NEAR(unreachable["frontier_area_m2"].get<double>(), area_m2, 1e-4);
  const std::vector<std::string> notes = run["steps"].back()["notes"];
  EXPECT_NE(std::find(notes.begin(), notes.end(), "terminated: done"), notes.end());
  EXPECT_NE(notes.front().find("the frontiers left are unreachable"), std::string::npos) << notes.front();
  EXPECT_NEAR(nlohmann::json::parse(r.out)["unreachable_frontier_area_m2"].get<double>(), area_m2, 0.01);
}

TEST(RunE2eTest, ObjectsWithoutAValidViewGetAnotherChanceBeforeUnreachableFrontiersEndTheRun) {
  fs::path dir;
  const std::string db = ScratchWithSmallDatabase("objscan_run_e2e_barrier", &dir);
  ASSERT_FALSE(db.empty());
  // A 4 m x 3 m room cut in two by a 0.9 m barrier (an object, not a wall): the robot sees over it but
  // cannot drive round it, so the low chair behind it has no reachable view and the floor behind it
  // leaves frontiers no path reaches.
  WriteText(dir / "room.yaml",
            "name: barrier_room\nwalls:\n  - {min: [-0.1, -0.1, 0], max: [4.1, 0, 2.5]}\n"
            "  - {min: [-0.1, 3, 0], max: [4.1, 3.1, 2.5]}\n  - {min: [-0.1, 0, 0], max: [0, 3, 2.5]}\n"
            "  - {min: [4, 0, 0], max: [4.1, 3, 2.5]}\nobjects:\n"
            "  - {box: [0.1, 3.0, 0.9], category: other, pose: [2.0, 1.5, 0, 0, 0, 0], name: barrier}\n"
            "  - {box: [0.5, 0.5, 0.9], category: chair, pose: [0.6, 0.6, 0, 0, 0, 0], name: chair_1}\n"
            "  - {box: [0.4, 0.4, 0.5], category: chair, pose: [3.3, 1.5, 0, 0, 0, 0], name: chair_2}\n");
  const Result r = RunObjscan("run --scene " + (dir / "room.yaml").string() + " --db " + db + " --quiet --out " +
                              (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json run = ReadJson(dir / "out" / "run.json");
  EXPECT_EQ(run["terminated"], "done");
  int chances = 0;
  for (const auto& step : run["steps"]) {
    for (const auto& note : step.value("notes", nlohmann::json::array())) {
      chances += note.get<std::string>().find("objects without a valid view get another chance") != std::string::npos;
    }
  }
  EXPECT_GE(chances, 1);
  // The chair behind the barrier is left for want of a reachable view, and said so. (This room once
  // passed on the far wall's depth noise taken for an object; that noise is structure now.)
  ASSERT_FALSE(run["unreachable"]["objects"].empty()) << run["unreachable"].dump();
  const int left = run["unreachable"]["objects"][0];
  bool listed = false;
  for (const auto& o : run["objects"]) {
    if (o["id"] != left) continue;
    listed = !o["complete"].get<bool>();
    EXPECT_EQ(o.value("gt_instance", 0), 8) << "the object left is chair_2 (instance 8): " << o.dump();
  }
  EXPECT_TRUE(listed);
}

}  // namespace
