#include "objscan/eval/report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "objscan/common/error.h"
#include "objscan/eval/plot.h"

namespace objscan::eval {
namespace {
namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("objscan_report_test_" + std::to_string(getpid()) + "_" + info->test_suite_name() + "_" + info->name());
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

// A hand-made run.json in the format `objscan run` writes.
struct Fixture {
  std::string spec = "procedural:bedroom:1";
  double recall = 0.5, precision = 0.25, recall_floor = 0.75, precision_floor = 0.5;
  int gt = 4, gt_floor = 2, outputs = 8, tp = 2;
  double rand_index = 0.8, rand_index_preseg = 0.6;
  // Steps: action, views, travel.
  std::vector<std::tuple<std::string, int, double>> steps = {{"frontier", 2, 0.0}, {"nbo", 1, 1.0}, {"nbv", 1, 0.5}};
  std::vector<std::pair<double, double>> coverage = {{0.1, 0.05}, {0.2, 0.1}, {0.4, 0.3}, {0.5, 0.4}};
  nlohmann::json per_category = {{"chair", {{"ground_truth", 3}, {"outputs", 5}, {"true_positives", 2}}},
                                 {"bed", {{"ground_truth", 1}, {"outputs", 3}, {"true_positives", 0}}}};
  double total_s = 10.0, navigate_s = 40.0;
  double peak_rss_mb = -1.0, cpu_s = -1.0;  // written when >= 0 (older run.json files lack them)

  std::string Json() const {
    nlohmann::json j;
    j["scene"] = spec;
    j["seed"] = 1;
    j["terminated"] = "done";
    nlohmann::json s = nlohmann::json::array();
    int index = 0;
    double travel = 0.0;
    for (const auto& [action, views, travel_m] : steps) {
      s.push_back({{"index", index++}, {"action", action}, {"ooi", -1}, {"views", views}, {"travel_m", travel_m},
                   {"timing_ms", {{"sense", 1.0}}}});
      travel += travel_m;
    }
    j["steps"] = s;
    j["objects"] = nlohmann::json::array();
    nlohmann::json cov = nlohmann::json::array();
    for (const auto& [r, q] : coverage) cov.push_back({r, q});
    int views = 0;
    for (const auto& st : steps) views += std::get<1>(st);
    j["metrics"] = {{"recall", recall},
                    {"precision", precision},
                    {"recall_floor", recall_floor},
                    {"precision_floor", precision_floor},
                    {"ground_truth_objects", gt},
                    {"ground_truth_floor_objects", gt_floor},
                    {"output_objects", outputs},
                    {"true_positives", tp},
                    {"rand_index", rand_index},
                    {"rand_index_preseg", rand_index_preseg},
                    {"preseg_purity", 1.0},
                    {"coverage_rate", coverage.empty() ? 0.0 : coverage.back().first},
                    {"coverage_quality", coverage.empty() ? 0.0 : coverage.back().second},
                    {"travel_m", travel},
                    {"views", views},
                    {"nbo_count", 1},
                    {"nbv_per_object", 1.0},
                    {"per_category", per_category},
                    {"coverage_per_view", cov}};
    j["timing_s"] = {{"total", total_s}, {"sense", 1.0},   {"fuse", 1.0}, {"segment", 2.0}, {"recognize", 5.0},
                     {"nbo", 0.5},       {"nbv", 0.5},     {"navigate_sim", navigate_s}};
    if (peak_rss_mb >= 0.0) j["peak_rss_mb"] = peak_rss_mb;
    if (cpu_s >= 0.0) j["cpu_s"] = cpu_s;
    return j.dump(2);
  }
};

TEST(ParseRunJsonTest, ReadsMetricsTimingAndCoverageWithTravelAndNboSwitches) {
  Fixture f;
  const RunSummary r = ParseRunJson(f.Json(), "scene-a", "ours", "fixture");
  EXPECT_EQ(r.scene_id, "scene-a");
  EXPECT_EQ(r.method, "ours");
  EXPECT_EQ(r.scene_category, "bedroom");
  EXPECT_EQ(r.terminated, "done");
  EXPECT_TRUE(r.has_metrics);
  EXPECT_DOUBLE_EQ(r.recall, 0.5);
  EXPECT_EQ(r.ground_truth_objects, 4);
  EXPECT_EQ(r.steps, 3);
  EXPECT_EQ(r.views, 4);
  EXPECT_DOUBLE_EQ(r.travel_m, 1.5);
  EXPECT_EQ(r.per_category.at("chair").outputs, 5);
  EXPECT_DOUBLE_EQ(r.timing_s.navigate_sim, 40.0);
  ASSERT_EQ(r.coverage.size(), 4u);
  // Views 1-2 are the look-around at 0 m; view 3 starts the NBO after 1 m; view 4 is its NBV.
  EXPECT_DOUBLE_EQ(r.coverage[1].travel_m, 0.0);
  EXPECT_FALSE(r.coverage[1].nbo_switch);
  EXPECT_DOUBLE_EQ(r.coverage[2].travel_m, 1.0);
  EXPECT_TRUE(r.coverage[2].nbo_switch);
  EXPECT_DOUBLE_EQ(r.coverage[3].travel_m, 1.5);
  EXPECT_FALSE(r.coverage[3].nbo_switch);
  EXPECT_DOUBLE_EQ(r.coverage[3].quality, 0.4);
  EXPECT_THROW(ParseRunJson("{\"scene\": 1}", "x", "ours", "bad.json"), InputError);
}

TEST(ParseRunJsonTest, ReadsRandIndexPerView) {
  Fixture f;
  nlohmann::json j = nlohmann::json::parse(f.Json());
  j["metrics"]["rand_index_per_view"] = {{16, 0.8}, {17, 0.85}, {20, 0.9}};
  const RunSummary r = ParseRunJson(j.dump(), "scene-a", "ours", "fixture");
  ASSERT_EQ(r.rand_index_per_view.size(), 3u);
  EXPECT_EQ(r.rand_index_per_view[1].first, 17);
  EXPECT_DOUBLE_EQ(r.rand_index_per_view[2].second, 0.9);
  // Old run.json files without it parse with an empty curve.
  EXPECT_TRUE(ParseRunJson(f.Json(), "scene-a", "ours", "fixture").rand_index_per_view.empty());
}

TEST(ReportTest, MeansPerSceneCategoryAndSumsPerObjectCategory) {
  Fixture a, b, c;
  b.spec = "procedural:bedroom:2";
  b.recall = 1.0;
  b.precision = 0.75;
  b.gt = 6;
  b.total_s = 30.0;
  b.per_category = {{"chair", {{"ground_truth", 2}, {"outputs", 2}, {"true_positives", 2}}}};
  c.spec = "procedural:office:1";
  c.recall = 0.2;
  std::vector<RunSummary> runs = {ParseRunJson(a.Json(), "bed-1", "ours", "a"),
                                  ParseRunJson(b.Json(), "bed-2", "ours", "b"),
                                  ParseRunJson(c.Json(), "off-1", "ours", "c"),
                                  ParseRunJson(c.Json(), "off-1", "frontier", "c")};
  RunSummary failed;
  failed.scene_id = "bed-3";
  failed.method = "ours";
  failed.scene_category = "bedroom";
  failed.failed = true;
  runs.push_back(failed);
  const Report report = BuildReport(runs);
  EXPECT_EQ(report.complete_runs, 4);
  EXPECT_EQ(report.failed_runs, 1);
  EXPECT_EQ(report.methods, (std::vector<std::string>{"ours", "frontier"}));
  EXPECT_EQ(report.scene_categories, (std::vector<std::string>{"bedroom", "office"}));
  const auto& ours = report.by_method.at("ours");
  ASSERT_EQ(ours.size(), 3u);  // bedroom, office, all
  EXPECT_EQ(ours[0].category, "bedroom");
  EXPECT_EQ(ours[0].scenes, 2);
  EXPECT_EQ(ours[0].failed, 1);
  EXPECT_DOUBLE_EQ(ours[0].recall, 0.75);
  EXPECT_DOUBLE_EQ(ours[0].precision, 0.5);
  EXPECT_DOUBLE_EQ(ours[0].objects_per_scene, 5.0);
  EXPECT_DOUBLE_EQ(ours[0].timing_s.total, 20.0);
  EXPECT_EQ(ours[2].category, "all");
  EXPECT_EQ(ours[2].scenes, 3);
  EXPECT_NEAR(ours[2].recall, (0.5 + 1.0 + 0.2) / 3, 1e-12);
  // Object categories of "ours": chair 3 + 2 + 3 ground truth, 5 + 2 + 5 outputs, 2 + 2 + 2 TP.
  ASSERT_EQ(report.object_categories.size(), 2u);
  EXPECT_EQ(report.object_categories[0].category, "bed");  // paper order: bed before chair
  const ObjectCategoryStats& chair = report.object_categories[1];
  EXPECT_EQ(chair.counts.ground_truth, 8);
  EXPECT_EQ(chair.counts.outputs, 12);
  EXPECT_EQ(chair.counts.true_positives, 6);
  EXPECT_DOUBLE_EQ(chair.recall, 0.75);
  EXPECT_DOUBLE_EQ(chair.precision, 0.5);
  EXPECT_DOUBLE_EQ(report.object_categories[0].recall, 0.0);
  // The markdown carries the paper's Table 1 figures beside ours.
  const std::string md = ReportMarkdown(report);
  EXPECT_NE(md.find("64.22%"), std::string::npos);
  EXPECT_NE(md.find("75.00%"), std::string::npos);
}

// Peak RSS and CPU time per method: means and maxima over the runs that recorded them; a run.json
// without them (older objscan) counts for neither.
TEST(ReportTest, ResourcesPerMethodFromRunJson) {
  Fixture a, b, old, f;
  a.cpu_s = 12.5;
  a.peak_rss_mb = 400.0;
  b.spec = "procedural:bedroom:2";
  b.cpu_s = 7.5;
  b.peak_rss_mb = 900.0;
  old.spec = "procedural:office:1";  // no resources recorded
  f.cpu_s = 3.0;
  f.peak_rss_mb = 250.0;
  const RunSummary parsed = ParseRunJson(a.Json(), "bed-1", "ours", "a");
  EXPECT_DOUBLE_EQ(parsed.cpu_s, 12.5);
  EXPECT_DOUBLE_EQ(parsed.peak_rss_mb, 400.0);
  const RunSummary parsed_old = ParseRunJson(old.Json(), "off-1", "ours", "old");
  EXPECT_LT(parsed_old.cpu_s, 0.0);
  EXPECT_LT(parsed_old.peak_rss_mb, 0.0);
  const Report report = BuildReport({parsed, ParseRunJson(b.Json(), "bed-2", "ours", "b"), parsed_old,
                                     ParseRunJson(f.Json(), "bed-1", "frontier", "f")});
  const SceneCategoryStats& ours = report.by_method.at("ours").back();
  EXPECT_EQ(ours.category, "all");
  EXPECT_EQ(ours.scenes, 3);
  EXPECT_EQ(ours.cpu_runs, 2);
  EXPECT_EQ(ours.rss_runs, 2);
  EXPECT_DOUBLE_EQ(ours.cpu_s, 10.0);
  EXPECT_DOUBLE_EQ(ours.cpu_s_max, 12.5);
  EXPECT_DOUBLE_EQ(ours.peak_rss_mb, 650.0);
  EXPECT_DOUBLE_EQ(ours.peak_rss_mb_max, 900.0);
  const SceneCategoryStats& frontier = report.by_method.at("frontier").back();
  EXPECT_DOUBLE_EQ(frontier.cpu_s, 3.0);
  EXPECT_DOUBLE_EQ(frontier.peak_rss_mb_max, 250.0);

  const std::string md = ReportMarkdown(report);
  EXPECT_NE(md.find("| `ours` | 3 | 10.0 | 12.5 | 10.0 | 650 | 900 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `frontier` | 1 | 3.0 | 3.0 | 10.0 | 250 | 250 |"), std::string::npos) << md;
  const nlohmann::json j = nlohmann::json::parse(ReportJson(report));
  const nlohmann::json& all = j["by_method"]["ours"].back();
  EXPECT_EQ(all["category"], "all");
  EXPECT_DOUBLE_EQ(all["resources"]["cpu_s"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(all["resources"]["peak_rss_mb_max"].get<double>(), 900.0);
  for (const auto& row : j["per_run"]) {
    if (row["scene"] == "bed-2") {
      EXPECT_DOUBLE_EQ(row["cpu_s"].get<double>(), 7.5);
    }
    if (row["scene"] == "off-1") {
      EXPECT_FALSE(row.contains("cpu_s"));
    }
  }
}

// Run A: V_S of 100 voxels, a chair (40, all seen, matched), a cabinet (60, 50 seen, taken for a
// dresser by the larger of two objects on it). Run B: a cabinet (10, all seen, matched) and a
// chair (30, 20 seen, on no object). Means over the two runs of the per-run shares.
TEST(ReportTest, CoverageBreakdownSharesVsByCategoryLikeTheCoverageRate) {
  Fixture a, b;
  b.spec = "procedural:bedroom:2";
  nlohmann::json ja = nlohmann::json::parse(a.Json()), jb = nlohmann::json::parse(b.Json());
  ja["metrics"]["instances"] = {
      {{"instance", 3}, {"category", "chair"}, {"surface_voxels", 40}, {"visible_voxels", 40}, {"matched", true}},
      {{"instance", 4}, {"category", "cabinet"}, {"surface_voxels", 60}, {"visible_voxels", 50}, {"matched", false}}};
  ja["objects"] = {{{"id", 1}, {"category", "chair"}, {"points", 900}, {"gt_instance", 3}},
                   {{"id", 2}, {"category", "dresser"}, {"points", 700}, {"gt_instance", 4}},
                   {{"id", 5}, {"category", nullptr}, {"points", 200}, {"gt_instance", 4}}};
  jb["metrics"]["instances"] = {
      {{"instance", 7}, {"category", "cabinet"}, {"surface_voxels", 10}, {"visible_voxels", 10}, {"matched", true}},
      {{"instance", 8}, {"category", "chair"}, {"surface_voxels", 30}, {"visible_voxels", 20}, {"matched", false}}};
  jb["objects"] = {{{"id", 1}, {"category", "cabinet"}, {"points", 300}, {"gt_instance", 7}}};
  const RunSummary ra = ParseRunJson(ja.dump(), "bed-1", "ours", "a");
  ASSERT_EQ(ra.instances.size(), 2u);
  EXPECT_EQ(ra.instances[1].reported_as, "dresser");
  const Report report = BuildReport({ra, ParseRunJson(jb.dump(), "bed-2", "ours", "b")});
  ASSERT_EQ(report.coverage_breakdown.size(), 2u);  // largest share of V_S first
  // The shares of a row, and the one label its missed surface went to.
  const auto expect_row = [](const CoverageBreakdownRow& row, const std::string& category, double surface,
                             double seen, double covered, const std::string& missed_as, double missed) {
    SCOPED_TRACE(category);
    EXPECT_EQ(row.category, category);
    EXPECT_DOUBLE_EQ(row.surface, surface);
    EXPECT_DOUBLE_EQ(row.seen, seen);
    EXPECT_DOUBLE_EQ(row.covered, covered);
    ASSERT_EQ(row.missed_as.size(), 1u);
    EXPECT_EQ(row.missed_as[0].first, missed_as);
    EXPECT_DOUBLE_EQ(row.missed_as[0].second, missed);
  };
  const CoverageBreakdownRow& chair = report.coverage_breakdown[0];
  const CoverageBreakdownRow& cabinet = report.coverage_breakdown[1];
  // Chair: surface (0.40 + 0.75) / 2, seen (0.40 + 0.50) / 2, covered 0.40 / 2; its unmatched
  // instance of run B lies on no object.
  expect_row(chair, "chair", 0.575, 0.45, 0.2, "not reported", 0.25);
  // Cabinet: surface (0.60 + 0.25) / 2, seen (0.50 + 0.25) / 2, covered (0 + 0.25) / 2.
  expect_row(cabinet, "cabinet", 0.425, 0.375, 0.125, "dresser", 0.25);
  // Summed, covered is the mean of the runs' covered shares (here (0.4 + 0.25) / 2).
  EXPECT_DOUBLE_EQ(cabinet.covered + chair.covered, 0.325);
  const std::string md = ReportMarkdown(report);
  EXPECT_NE(md.find("| Cabinet | 42.50 | 37.50 | 12.50 | 25.00 | Dresser 25.00 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| **All** | 100.00 | 82.50 | 32.50 | 50.00 | |"), std::string::npos) << md;
  const nlohmann::json j = nlohmann::json::parse(ReportJson(report));
  EXPECT_EQ(j["coverage_breakdown"][0]["category"], "chair");
  EXPECT_DOUBLE_EQ(j["coverage_breakdown"][0]["covered"].get<double>(), 0.2);
  // Runs without instances (older run.json files) leave the breakdown out.
  EXPECT_TRUE(BuildReport({ParseRunJson(a.Json(), "bed-1", "ours", "a")}).coverage_breakdown.empty());
  EXPECT_EQ(ReportMarkdown(BuildReport({ParseRunJson(a.Json(), "bed-1", "ours", "a")})).find("Where the coverage"),
            std::string::npos);
}

TEST(ReportTest, CurvesHoldTheLastValueOfShorterRuns) {
  Fixture a, b;
  b.steps = {{"frontier", 1, 0.0}, {"nbo", 1, 2.0}};
  b.coverage = {{0.3, 0.2}, {0.7, 0.6}};
  const RunSummary ra = ParseRunJson(a.Json(), "a", "ours", "a");
  const RunSummary rb = ParseRunJson(b.Json(), "b", "ours", "b");
  const Curve views = MeanCoverageOverViews({&ra, &rb}, false);
  ASSERT_EQ(views.x.size(), 4u);
  EXPECT_DOUBLE_EQ(views.y[0], (0.1 + 0.3) / 2);
  EXPECT_DOUBLE_EQ(views.y[3], (0.5 + 0.7) / 2);
  // Travel 0..2 m in 5 samples: a reaches 1 m (0.4) and 1.5 m (0.5); b jumps at 2 m.
  const Curve travel = MeanCoverageOverTravel({&ra, &rb}, 5, false);
  ASSERT_EQ(travel.x.size(), 5u);
  EXPECT_DOUBLE_EQ(travel.x[4], 2.0);
  EXPECT_DOUBLE_EQ(travel.y[0], (0.2 + 0.3) / 2);
  EXPECT_DOUBLE_EQ(travel.y[2], (0.4 + 0.3) / 2);
  EXPECT_DOUBLE_EQ(travel.y[3], (0.5 + 0.3) / 2);
  EXPECT_DOUBLE_EQ(travel.y[4], (0.5 + 0.7) / 2);
  // Quality before the first NBO and at the end: a (0.1, 0.4), b (0.2, 0.6).
  const Curve nbos = MeanQualityOverNbos({&ra, &rb});
  ASSERT_EQ(nbos.x.size(), 2u);
  EXPECT_DOUBLE_EQ(nbos.y[0], (0.1 + 0.2) / 2);
  EXPECT_DOUBLE_EQ(nbos.y[1], (0.4 + 0.6) / 2);
}

// Six runs of two methods over three scenes.
std::vector<std::pair<fs::path, std::string>> FixtureRuns() {
  std::vector<std::pair<fs::path, std::string>> runs;
  int k = 0;
  for (const char* spec : {"procedural:bedroom:1", "procedural:kitchen:1", "procedural:office:2"}) {
    for (const char* method : {"ours", "preseg-only"}) {
      Fixture f;
      f.spec = spec;
      f.recall = 0.1 * ++k;
      f.rand_index = 0.5 + 0.03 * k;
      f.total_s = 3.0 * k;
      std::string id = std::string(spec).substr(11);
      std::replace(id.begin(), id.end(), ':', '-');
      runs.push_back({fs::path("runs") / id / method, f.Json()});
    }
  }
  return runs;
}

TEST(ReportTest, ShardsMergeToTheSameReportAsOneBench) {
  TempDir dir;
  const auto runs = FixtureRuns();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    WriteText(dir.path() / "whole" / runs[i].first / "run.json", runs[i].second);
    WriteText(dir.path() / (i % 2 ? "shard2" : "shard1") / runs[i].first / "run.json", runs[i].second);
  }
  // Leftovers that must not change anything: a failure record superseded by a complete run, and a
  // report folder from an earlier report.
  WriteText(dir.path() / "shard2" / runs[0].first / "failed.json", R"({"exit_code": 1})");
  WriteText(dir.path() / "whole" / "report" / "runs" / "x" / "ours" / "run.json", "garbage");
  const std::string whole = ReportJson(BuildReport(CollectRuns({(dir.path() / "whole").string()})));
  const std::string merged = ReportJson(
      BuildReport(CollectRuns({(dir.path() / "shard1").string(), (dir.path() / "shard2").string()})));
  EXPECT_EQ(whole, merged);
  const nlohmann::json j = nlohmann::json::parse(whole);
  EXPECT_EQ(j["runs"]["complete"], 6);
  EXPECT_EQ(j["runs"]["failed"], 0);
  // One shard alone is a different report.
  const std::string one = ReportJson(BuildReport(CollectRuns({(dir.path() / "shard1").string()})));
  EXPECT_NE(whole, one);
}

TEST(ReportTest, WhatRunsCouldNotReachIsListedApart) {
  TempDir dir;
  Fixture house;
  house.spec = "house.world";
  nlohmann::json j = nlohmann::json::parse(house.Json());
  j["unreachable"] = {{"frontier_area_m2", 0.35},
                      {"frontiers", nlohmann::json::array({{{"xy_m", {1.0, 2.0}}, {"cells", 140}, {"area_m2", 0.35}}})},
                      {"objects", {17, 42}}};
  j["metrics"]["never_seen"] = nlohmann::json::array({{{"instance", 4}, {"name", "Wardrobe_01_001"}, {"category", "cabinet"}}});
  j["metrics"]["reachable"] = {{"ground_truth_objects", 3}, {"output_objects", 8}, {"true_positives", 2},
                               {"recall", 2.0 / 3.0}, {"precision", 0.25}};
  j["metrics"]["unreachable_rooms"] = nlohmann::json::array(
      {{{"room", 1}, {"area_m2", 20.3}, {"center_m", {-6.3, 4.8}},
        {"objects", nlohmann::json::array({{{"instance", 9}, {"name", "Bed_01_001"}, {"category", "bed"}}})}}});
  WriteText(dir.path() / "house" / "run.json", j.dump(2));
  // Reached everything but the floor outside the walls (a room without objects): not listed.
  nlohmann::json room = nlohmann::json::parse(Fixture().Json());
  room["metrics"]["unreachable_rooms"] = nlohmann::json::array(
      {{{"room", 2}, {"area_m2", 13.9}, {"center_m", {7.5, 4.8}}, {"objects", nlohmann::json::array()}}});
  WriteText(dir.path() / "room" / "run.json", room.dump(2));
  const std::vector<RunSummary> runs = CollectRuns({dir.path().string()});
  ASSERT_EQ(runs.size(), 2u);
  const RunSummary& r = runs[0].scene_id == "house" ? runs[0] : runs[1];
  EXPECT_TRUE(r.ReachedLess());
  EXPECT_EQ(r.unreachable_frontiers, 1);
  EXPECT_DOUBLE_EQ(r.unreachable_frontier_area_m2, 0.35);
  EXPECT_EQ(r.objects_left, (std::vector<int>{17, 42}));
  ASSERT_EQ(r.unreachable_rooms.size(), 1u);
  EXPECT_EQ(r.unreachable_rooms[0].objects, (std::vector<std::string>{"Bed_01_001 (bed)"}));
  EXPECT_TRUE(r.has_reachable);
  EXPECT_EQ(r.ground_truth_reachable, 3);
  const Report report = BuildReport(runs);
  const std::string md = ReportMarkdown(report);
  EXPECT_NE(md.find("## What the runs could not reach"), std::string::npos);
  EXPECT_NE(md.find("| house | `ours` | done | room 1 (20.3 m2): Bed_01_001 (bed) | 66.67% / 25.00% (3 objects) | "
                    "1 (0.35 m2) | 17, 42 | Wardrobe_01_001 (cabinet) |"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("| room | `ours` | done | -"), std::string::npos);
  const nlohmann::json results = nlohmann::json::parse(ReportJson(report));
  ASSERT_EQ(results["unreachable"].size(), 1u);
  EXPECT_EQ(results["unreachable"][0]["scene"], "house");
  EXPECT_EQ(results["unreachable"][0]["objects_left"], nlohmann::json({17, 42}));
  // A report of runs that reached everything has no such section.
  EXPECT_EQ(ReportMarkdown(BuildReport({runs[0].scene_id == "room" ? runs[0] : runs[1]})).find("could not reach"),
            std::string::npos);
}

TEST(ReportTest, FoldersWithoutRunsAreNamed) {
  TempDir dir;
  fs::create_directories(dir.path() / "empty" / "sub");
  WriteText(dir.path() / "bench" / "runs" / "a" / "ours" / "failed.json", "{\"exit_code\": 1}");
  WriteText(dir.path() / "old" / "report" / "run.json", Fixture().Json());  // a report folder is no run
  EXPECT_EQ(FoldersWithoutRuns({(dir.path() / "bench").string()}).size(), 0u);
  EXPECT_EQ(FoldersWithoutRuns({(dir.path() / "empty").string(), (dir.path() / "bench").string(),
                                (dir.path() / "old").string()}),
            (std::vector<std::string>{(dir.path() / "empty").string(), (dir.path() / "old").string()}));
  EXPECT_THROW(FoldersWithoutRuns({(dir.path() / "typo").string()}), InputError);
}

TEST(ReportTest, FailedRunsAreReported) {
  TempDir dir;
  Fixture f;
  WriteText(dir.path() / "runs" / "bedroom-1" / "ours" / "run.json", f.Json());
  WriteText(dir.path() / "runs" / "bedroom-2" / "ours" / "failed.json",
            R"({"scene": "procedural:bedroom:2", "exit_code": 2})");
  const Report report = BuildReport(CollectRuns({dir.path().string()}));
  ASSERT_EQ(report.runs.size(), 2u);
  EXPECT_TRUE(report.runs[1].failed);
  EXPECT_EQ(report.runs[1].exit_code, 2);
  EXPECT_EQ(report.runs[1].scene_category, "bedroom");
  EXPECT_EQ(report.by_method.at("ours")[0].failed, 1);
  EXPECT_EQ(report.by_method.at("ours")[0].scenes, 1);
  EXPECT_THROW(CollectRuns({(dir.path() / "missing").string()}), InputError);
}

TEST(ReportTest, WritesTablesAndPlots) {
  TempDir dir;
  for (const auto& [path, text] : FixtureRuns()) WriteText(dir.path() / path / "run.json", text);
  const Report report = BuildReport(CollectRuns({dir.path().string()}));
  const auto files = WriteReport(report, (dir.path() / "report").string());
  EXPECT_GE(files.size(), 2u + 2u * 10u);
  for (const auto& f : files) EXPECT_GT(fs::file_size(dir.path() / "report" / f), 100u) << f;
  const std::string svg = ReadText(dir.path() / "report" / "fig10a_rand_index.svg");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("preseg-only"), std::string::npos);
}

// Three finished runs in a bench folder, with the reported objects and ground-truth instances of
// run.json (error_analysis_test.cc has the same room 1 as typed data):
//  - bedroom-1 / ours: chairs 1, 2, bed 3, plant 4 (`other`), lamp 5, table 6, box 10 (`other`), and
//    a wall 9 (not listed: run.json lists non-structural instances). Reported: chair on 1 (correct),
//    chair on 1 (duplicate), radio on 2 (wrong), chair on 4 (other), table on no instance
//    (background), bed on the wall 9 (structure), lamp on 3 (duplicate of the bed reported next),
//    bed on 3 (correct), table on 42 (background), table on 6 (correct); not counted: an incomplete
//    sofa below the default objectness 0.5, and an unlabelled object on lamp 5. Lamp 5, box 10 missed.
//  - bedroom-2 / ours (eval.recognized_min_objectness 0.25): chair 7, sofa 8. Sofa on 8 (correct), an
//    incomplete chair on 8 at objectness 0.3 (counted: a duplicate); chair 7 missed.
//  - bedroom-1 / frontier: chair 1, reported as a chair (correct).
std::vector<std::pair<fs::path, std::string>> ErrorAnalysisRuns() {
  auto run = [](const std::string& spec, double recall, int gt, int outputs, int tp, const nlohmann::json& instances,
                const nlohmann::json& objects) {
    Fixture f;
    f.spec = spec;
    f.recall = recall;
    f.gt = gt;
    f.outputs = outputs;
    f.tp = tp;
    f.precision = outputs ? double(tp) / outputs : 0.0;
    nlohmann::json j = nlohmann::json::parse(f.Json());
    j["metrics"]["instances"] = instances;
    j["objects"] = objects;
    return j;
  };
  auto instance = [](int id, const std::string& category, bool in_database) {
    return nlohmann::json{{"instance", id}, {"category", category}, {"in_database", in_database},
                          {"surface_voxels", 10}, {"visible_voxels", 5}, {"matched", false}};
  };
  auto object = [](int id, const nlohmann::json& category, int gt_instance, bool complete = true,
                   double objectness = 0.97) {
    nlohmann::json o{{"id", id}, {"category", category}, {"complete", complete}, {"objectness", objectness},
                     {"points", 100}};
    if (gt_instance > 0) o["gt_instance"] = gt_instance;
    return o;
  };
  const nlohmann::json room1 = run(
      "procedural:bedroom:1", 0.5, 5, 10, 3,
      {instance(1, "chair", true), instance(2, "chair", true), instance(3, "bed", true), instance(4, "other", false),
       instance(5, "lamp", true), instance(6, "table", true), instance(10, "other", false)},
      {object(1, "chair", 1), object(2, "chair", 1), object(3, "radio", 2), object(4, "chair", 4),
       object(5, "table", 0), object(6, "bed", 9), object(7, "lamp", 3), object(8, "bed", 3), object(9, "table", 42),
       object(10, "table", 6), object(11, "sofa", 2, false, 0.3), object(12, nullptr, 5)});
  nlohmann::json room2 =
      run("procedural:bedroom:2", 0.5, 2, 2, 1, {instance(7, "chair", true), instance(8, "sofa", true)},
          {object(1, "sofa", 8), object(2, "chair", 8, false, 0.3)});
  room2["config"] = {{"eval", {{"recognized_min_objectness", 0.25}}}};
  const nlohmann::json frontier =
      run("procedural:bedroom:1", 1.0, 1, 1, 1, nlohmann::json::array({instance(1, "chair", true)}),
          nlohmann::json::array({object(1, "chair", 1)}));
  return {{fs::path("runs") / "bedroom-1" / "ours", room1.dump(2)},
          {fs::path("runs") / "bedroom-2" / "ours", room2.dump(2)},
          {fs::path("runs") / "bedroom-1" / "frontier", frontier.dump(2)}};
}

TEST(ReportTest, ErrorClassesAndConfusionMatrixOfReportedObjects) {
  TempDir dir;
  for (const auto& [path, text] : ErrorAnalysisRuns()) WriteText(dir.path() / path / "run.json", text);
  const Report report = BuildReport(CollectRuns({dir.path().string()}));
  ASSERT_EQ(report.runs.size(), 3u);
  using O = OutputOutcome;
  // Per run: the classes sum to the run's outputs, and `correct` is its true positives.
  for (const RunSummary& r : report.runs) {
    SCOPED_TRACE(r.scene_id + "/" + r.method);
    ASSERT_TRUE(r.has_error_analysis);
    EXPECT_EQ(r.errors.Count(O::kCorrect), r.true_positives);
    EXPECT_EQ(r.errors.Total(), r.output_objects);
  }
  const RunSummary& room1 = report.runs[1];  // sorted by (scene, method): frontier before ours
  ASSERT_EQ(room1.method, "ours");
  EXPECT_EQ(room1.errors.counts, (std::array<int, kNumOutputOutcomes>{3, 3, 2, 1, 1}));

  // Per method and overall, summed.
  ASSERT_EQ(report.errors.size(), 3u);
  EXPECT_EQ(report.errors[0].method, "ours");
  EXPECT_EQ(report.errors[0].runs, 2);
  const ErrorBreakdown& ours = report.errors[0].breakdown;
  EXPECT_EQ(ours.Count(O::kCorrect), 4);
  EXPECT_EQ(ours.Count(O::kWrongCategory), 1);
  EXPECT_EQ(ours.Count(O::kDuplicatePiece), 3);
  EXPECT_EQ(ours.Count(O::kOtherObject), 1);
  EXPECT_EQ(ours.Count(O::kBackgroundOrStructure), 3);
  EXPECT_EQ(report.errors[1].method, "frontier");
  EXPECT_EQ(report.errors[1].breakdown.Count(O::kCorrect), 1);
  EXPECT_EQ(report.errors[2].method, "all");
  EXPECT_EQ(report.errors[2].runs, 3);
  EXPECT_EQ(report.errors[2].breakdown.Total(), 13);
  EXPECT_EQ(report.errors[2].breakdown.Count(O::kCorrect), 5);

  // confusion.csv, cell by cell: one header (the columns of every method), the rows of each method,
  // then "all".
  const auto files = WriteReport(report, (dir.path() / "report").string());
  EXPECT_NE(std::find(files.begin(), files.end(), "confusion.csv"), files.end());
  EXPECT_EQ(ReadText(dir.path() / "report" / "confusion.csv"),
            "method,ground_truth,bed,chair,lamp,radio,sofa,table,missed,total\n"
            "ours,bed,1,0,1,0,0,0,0,2\n"
            "ours,chair,0,2,0,1,0,0,1,4\n"
            "ours,lamp,0,0,0,0,0,0,1,1\n"
            "ours,sofa,0,1,0,0,1,0,0,2\n"
            "ours,table,0,0,0,0,0,1,0,1\n"
            "ours,other,0,1,0,0,0,0,1,2\n"
            "ours,background/structure,1,0,0,0,0,2,0,3\n"
            "frontier,chair,0,1,0,0,0,0,0,1\n"
            "all,bed,1,0,1,0,0,0,0,2\n"
            "all,chair,0,3,0,1,0,0,1,5\n"
            "all,lamp,0,0,0,0,0,0,1,1\n"
            "all,sofa,0,1,0,0,1,0,0,2\n"
            "all,table,0,0,0,0,0,1,0,1\n"
            "all,other,0,1,0,0,0,0,1,2\n"
            "all,background/structure,1,0,0,0,0,2,0,3\n");

  // results.md: the classes per method and overall, the matrix of `ours`, the classes per run.
  const std::string md = ReadText(dir.path() / "report" / "results.md");
  EXPECT_NE(md.find("| `ours` | 2 | 12 | 4 (33.33%) | 1 (8.33%) | 3 (25.00%) | 1 (8.33%) | 3 (25.00%) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| **All methods** | 3 | 13 | 5 (38.46%) | 1 (7.69%) | 3 (23.08%) | 1 (7.69%) | 3 (23.08%) |"),
            std::string::npos);
  EXPECT_NE(md.find("## Confusion matrix (`ours`"), std::string::npos);
  EXPECT_NE(md.find("| ground truth \\ reported | Bed | Chair | Lamp | Radio | Sofa | Table | Missed | total |"),
            std::string::npos);
  EXPECT_NE(md.find("| Chair |  | **2** |  | 1 |  |  | 1 | 4 |"), std::string::npos);
  EXPECT_NE(md.find("| Background/structure | 1 |  |  |  |  | 2 |  | 3 |"), std::string::npos);
  EXPECT_NE(md.find("| total | 2 | 4 | 1 | 1 | 1 | 3 | 3 | |"), std::string::npos);
  EXPECT_NE(md.find("| 10: 3 / 1 / 2 / 1 / 3 |"), std::string::npos);
  EXPECT_EQ(md.find("On a piece"), std::string::npos);  // no run records gt_instance_share

  // results.json and the JSON the commands print.
  const nlohmann::json j = nlohmann::json::parse(ReadText(dir.path() / "report" / "results.json"));
  const nlohmann::json& reported = j["reported_objects"];
  EXPECT_EQ(reported["classes"], nlohmann::json({"correct", "wrong_category", "duplicate_piece", "other_object",
                                                 "background_or_structure"}));
  EXPECT_EQ(reported["by_method"][0]["method"], "ours");
  EXPECT_EQ(reported["by_method"][0]["reported"], 12);
  EXPECT_DOUBLE_EQ(reported["by_method"][0]["shares"]["duplicate_piece"].get<double>(), 0.25);
  EXPECT_EQ(reported["overall"]["counts"]["correct"], 5);
  EXPECT_EQ(reported, nlohmann::json::parse(ReportedObjectsJson(report)));
  EXPECT_EQ(j["confusion"]["frontier"]["rows"], nlohmann::json({"chair"}));
  EXPECT_EQ(j["confusion"]["frontier"]["counts"], nlohmann::json({{1}}));
  EXPECT_EQ(j["confusion"]["ours"]["columns"].back(), "missed");
  EXPECT_EQ(j["per_run"][1]["reported_objects"]["counts"]["background_or_structure"], 3);
}

// Runs that record each object's share of its ground-truth object (gt_instance_share) get the "on a
// piece" counts per class: room 2's sofa holds 0.8 of the sofa (correct, whole), its chair-labelled
// second piece 0.2 of it (a duplicate piece on a piece); room 1 records no shares.
TEST(ReportTest, OutputsOnAPieceOfTheirObjectAreCountedPerClass) {
  TempDir dir;
  for (auto [path, text] : ErrorAnalysisRuns()) {
    if (path == fs::path("runs") / "bedroom-2" / "ours") {
      nlohmann::json j = nlohmann::json::parse(text);
      j["objects"][0]["gt_instance_share"] = 0.8;
      j["objects"][1]["gt_instance_share"] = 0.2;
      text = j.dump(2);
    }
    WriteText(dir.path() / path / "run.json", text);
  }
  const Report report = BuildReport(CollectRuns({dir.path().string()}));
  ASSERT_EQ(report.errors.size(), 3u);
  const ErrorBreakdown& ours = report.errors[0].breakdown;
  EXPECT_EQ(ours.share_known, 2);
  EXPECT_EQ(ours.on_piece, (std::array<int, kNumOutputOutcomes>{0, 0, 1, 0, 0}));
  EXPECT_EQ(report.errors[1].breakdown.share_known, 0);  // frontier
  EXPECT_EQ(report.errors[2].breakdown.OnPiece(OutputOutcome::kDuplicatePiece), 1);

  const std::string md = ReportMarkdown(report);
  EXPECT_NE(md.find("| Method | share known | correct, on a piece | wrong category, on a piece | duplicate piece, on a "
                    "piece | `other` object, on a piece |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| `ours` | 2 | 0 | 0 | 1 | 0 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `frontier` | 0 | 0 | 0 | 0 | 0 |"), std::string::npos);
  const nlohmann::json reported = nlohmann::json::parse(ReportedObjectsJson(report));
  EXPECT_EQ(reported["by_method"][0]["share_known"], 2);
  EXPECT_EQ(reported["by_method"][0]["on_piece"]["duplicate_piece"], 1);
  EXPECT_FALSE(reported["by_method"][1].contains("on_piece"));
}

TEST(ReportTest, NoErrorAnalysisWithoutInstancesAndUnknownCategoriesThrow) {
  TempDir dir;
  // Older run.json files (no metrics.instances): no classes, no matrix, no confusion.csv.
  Fixture f;
  WriteText(dir.path() / "runs" / "bedroom-1" / "ours" / "run.json", f.Json());
  const Report report = BuildReport(CollectRuns({dir.path().string()}));
  EXPECT_FALSE(report.runs[0].has_error_analysis);
  EXPECT_TRUE(report.errors.empty());
  EXPECT_EQ(ConfusionCsv(report), "");
  const auto files = WriteReport(report, (dir.path() / "report").string());
  EXPECT_EQ(std::find(files.begin(), files.end(), "confusion.csv"), files.end());
  EXPECT_FALSE(fs::exists(dir.path() / "report" / "confusion.csv"));
  EXPECT_EQ(ReportMarkdown(report).find("Confusion matrix"), std::string::npos);
  EXPECT_FALSE(nlohmann::json::parse(ReportJson(report)).contains("reported_objects"));
  // A category objscan does not know is bad input, named with its file.
  nlohmann::json j = nlohmann::json::parse(f.Json());
  j["metrics"]["instances"] = {{{"instance", 1}, {"category", "spaceship"}}};
  try {
    ParseRunJson(j.dump(), "x", "ours", "odd/run.json");
    FAIL() << "no throw";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("odd/run.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("spaceship"), std::string::npos) << e.what();
  }
}

TEST(PlotTest, NiceTicksCoverTheRangeWithRoundSteps) {
  const auto t = NiceTicks(0.0, 1.0, 6);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_DOUBLE_EQ(t.front(), 0.0);
  EXPECT_DOUBLE_EQ(t[1], 0.2);
  EXPECT_NEAR(t.back(), 1.0, 1e-12);
  const auto u = NiceTicks(3.0, 47.0, 6);
  EXPECT_LE(u.front(), 3.0);
  EXPECT_GE(u.back(), 47.0);
  EXPECT_DOUBLE_EQ(u[1] - u[0], 10.0);
  const auto flat = NiceTicks(2.0, 2.0, 6);
  EXPECT_LE(flat.front(), 2.0);
  EXPECT_GE(flat.back(), 2.0);
  EXPECT_GE(flat.size(), 2u);
}

TEST(PlotTest, LineAndBarPlotsDrawTheirData) {
  LinePlot line;
  line.title = "t";
  line.series.push_back(PlotSeries::Line("s", {0, 1, 2}, {0, 1, 0}, {200, 0, 0}));
  line.series[0].highlight_x = {1};
  line.series[0].highlight_y = {1};
  const io::Canvas canvas = RenderCanvas(line);
  int red_pixels = 0;
  for (int y = 0; y < canvas.height(); ++y) {
    for (int x = 0; x < canvas.width(); ++x) {
      const io::Rgb p = canvas.Pixel(x, y);
      red_pixels += p[0] > 180 && p[1] < 60 && p[2] < 60;
    }
  }
  EXPECT_GT(red_pixels, 100);
  const std::string svg = RenderSvg(line);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_NE(svg.find("<circle"), std::string::npos);
  BarPlot bars;
  bars.groups = {"a", "b"};
  bars.series.push_back({"v", {1.0, std::nan("")}, {0, 0, 200}});
  const std::string bar_svg = RenderSvg(bars);
  // One bar for group a (the NaN of group b is left out) plus the legend swatch and background.
  std::size_t rects = 0;
  for (std::size_t p = bar_svg.find("<rect"); p != std::string::npos; p = bar_svg.find("<rect", p + 1)) ++rects;
  EXPECT_EQ(rects, 3u);
}

}  // namespace
}  // namespace objscan::eval
