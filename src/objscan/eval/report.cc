#include "objscan/eval/report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "objscan/common/error.h"
#include "objscan/eval/benchmark.h"
#include "objscan/eval/report_internal.h"
#include "objscan/scanning/system_config.h"
#include "objscan/world/category.h"

namespace objscan::eval {
namespace fs = std::filesystem;
using namespace report_internal;  // NOLINT: the report files share these helpers
using Json = nlohmann::ordered_json;

// The paper's published figures (Liu et al. 2018, "Object-aware guidance for autonomous scene
// reconstruction", /work/shared/paper/object-aware-guidance.tex): Table 1 (recognition per scene
// category), Table 2 (per object category) and Table 3 (running time in minutes, virtual scenes).
const std::vector<PaperSceneRow>& PaperTable1() {
  static const std::vector<PaperSceneRow> kRows = {
      {"bedroom", 21, 11, 64.22, 86.13, 76.41, 93.13},     {"living_room", 24, 15, 65.27, 58.40, 71.91, 60.21},
      {"kitchen", 20, 15, 55.78, 66.65, 73.47, 76.82},     {"bathroom", 19, 6, 81.74, 84.68, 83.19, 85.45},
      {"office", 20, 11, 74.77, 78.81, 85.56, 87.91},
  };
  return kRows;
}

const std::vector<PaperObjectRow>& PaperTable2() {
  static const std::vector<PaperObjectRow> kRows = {
      {"bathtub", 19, 84.21, 80.0},       {"bed", 22, 77.27, 89.47},         {"cabinet", 84, 63.10, 53.54},
      {"can", 9, 100.0, 75.0},            {"chair", 140, 86.43, 90.30},      {"curtain", 14, 64.29, 52.94},
      {"desk", 74, 75.68, 78.87},         {"door", 76, 40.79, 44.28},        {"dresser", 16, 81.25, 72.22},
      {"lamp", 20, 75.0, 75.0},           {"monitor", 113, 67.26, 61.79},    {"night_stand", 27, 77.78, 80.77},
      {"radio", 39, 71.79, 77.78},        {"refrigerator", 12, 58.33, 63.64}, {"shelves", 70, 70.0, 74.24},
      {"sink", 15, 93.33, 100.0},         {"sofa", 45, 88.89, 85.11},        {"table", 96, 83.33, 81.63},
      {"toilet", 17, 82.35, 93.33},       {"tv_stand", 49, 77.55, 76.0},     {"window", 53, 52.83, 56.0},
      {"other", 211, 33.18, 56.45},
  };
  return kRows;
}

const std::vector<PaperTimingRow>& PaperTable3() {
  static const std::vector<PaperTimingRow> kRows = {
      {"bedroom", 47.8, 24.1, 20.1, 2.0, 1.6},  {"living_room", 57.0, 30.4, 22.2, 2.3, 2.1},
      {"kitchen", 37.5, 16.2, 17.6, 2.0, 1.7},  {"bathroom", 29.5, 14.8, 12.2, 1.3, 1.2},
      {"office", 40.8, 21.3, 16.0, 1.9, 1.6},
  };
  return kRows;
}

namespace {

double Num(const Json& j, const char* key) {
  auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : 0.0;
}
int Int(const Json& j, const char* key) { return static_cast<int>(std::lround(Num(j, key))); }

world::Category CategoryNamed(const std::string& name, const std::string& source) {
  const std::optional<world::Category> c = world::ParseCategory(name);
  if (!c) throw InputError(source + ": unknown category \"" + name + "\"");
  return *c;
}

// The error analysis of a run from its objects and ground-truth instances. The outputs are taken as
// RunEvaluator takes them (labelled; complete, or objectness >= the run's
// eval.recognized_min_objectness) and in the same order, so the classes agree with its precision.
void AnalyseRunErrors(const Json& j, const std::string& source, RunSummary* r) {
  std::vector<GroundTruthInstance> truth;
  std::set<world::Category> database;
  for (const Json& i : j["metrics"]["instances"]) {
    if (!i.is_object() || !i.contains("instance") || !i["instance"].is_number()) continue;
    GroundTruthInstance g;
    g.instance_id = i["instance"].get<int>();
    g.category = CategoryNamed(i.value("category", std::string()), source);
    // Older run.json files do not say; the database knew the categories of nearly every instance.
    if (!i.contains("in_database") || (i["in_database"].is_boolean() && i["in_database"].get<bool>())) {
      database.insert(g.category);
    }
    truth.push_back(g);
  }
  double min_objectness = scanning::EvaluationOptions{}.recognized_min_objectness;
  if (j.contains("config") && j["config"].is_object() && j["config"].contains("eval") &&
      j["config"]["eval"].is_object()) {
    const Json& eval = j["config"]["eval"];
    if (eval.contains("recognized_min_objectness") && eval["recognized_min_objectness"].is_number()) {
      min_objectness = eval["recognized_min_objectness"].get<double>();
    }
  }
  std::vector<OutputObject> outputs;
  if (j.contains("objects") && j["objects"].is_array()) {
    for (const Json& o : j["objects"]) {
      if (!o.is_object() || !o.contains("category") || !o["category"].is_string()) continue;
      const bool complete = o.contains("complete") && o["complete"].is_boolean() && o["complete"].get<bool>();
      if (!complete && Num(o, "objectness") < min_objectness) continue;
      OutputObject out;
      out.category = CategoryNamed(o["category"].get<std::string>(), source);
      if (!IsScoredCategory(out.category)) continue;  // recognised as `other`: no output
      out.majority_instance = o.contains("gt_instance") && o["gt_instance"].is_number() ? o["gt_instance"].get<int>()
                                                                                       : world::kNoInstance;
      if (o.contains("gt_instance_share") && o["gt_instance_share"].is_number()) {
        out.instance_share = o["gt_instance_share"].get<double>();
      }
      outputs.push_back(out);
    }
  }
  ErrorAnalysis analysis;
  try {
    analysis = AnalyseErrors(truth, outputs, std::vector<world::Category>(database.begin(), database.end()));
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
  r->has_error_analysis = true;
  r->errors = analysis.breakdown;
  r->confusion = std::move(analysis.confusion);
}

}  // namespace

RunSummary ParseRunJson(const std::string& text, const std::string& scene_id, const std::string& method,
                        const std::string& source) {
  const Json j = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("terminated") || !j.contains("timing_s")) {
    throw InputError(source + ": not a complete run.json");
  }
  RunSummary r;
  r.scene_id = scene_id;
  r.method = method;
  r.scene_spec = j.value("scene", std::string());
  r.scene_category = SceneCategoryOfSpec(r.scene_spec);
  r.terminated = j["terminated"].is_string() ? j["terminated"].get<std::string>() : "";
  // Views of each step: their travel so far and whether the step switched to a next best object.
  std::vector<double> view_travel;
  std::vector<bool> view_nbo;
  double travel = 0.0;
  if (j.contains("steps") && j["steps"].is_array()) {
    for (const Json& s : j["steps"]) {
      ++r.steps;
      travel += Num(s, "travel_m");
      const int views = Int(s, "views");
      const bool nbo = s.value("action", std::string()) == "nbo";
      for (int k = 0; k < views; ++k) {
        view_travel.push_back(travel);
        view_nbo.push_back(nbo && k == 0);
      }
    }
  }
  if (j.contains("unreachable") && j["unreachable"].is_object()) {
    const Json& u = j["unreachable"];
    r.unreachable_frontier_area_m2 = Num(u, "frontier_area_m2");
    r.unreachable_frontiers = u.contains("frontiers") && u["frontiers"].is_array() ? static_cast<int>(u["frontiers"].size()) : 0;
    if (u.contains("objects") && u["objects"].is_array()) {
      for (const Json& id : u["objects"]) {
        if (id.is_number_integer()) r.objects_left.push_back(id.get<int>());
      }
    }
  }
  if (j.contains("metrics") && j["metrics"].is_object()) {
    const Json& m = j["metrics"];
    r.has_metrics = true;
    r.recall = Num(m, "recall");
    r.precision = Num(m, "precision");
    r.recall_floor = Num(m, "recall_floor");
    r.precision_floor = Num(m, "precision_floor");
    r.ground_truth_objects = Int(m, "ground_truth_objects");
    r.ground_truth_floor_objects = Int(m, "ground_truth_floor_objects");
    r.output_objects = Int(m, "output_objects");
    r.true_positives = Int(m, "true_positives");
    r.rand_index = Num(m, "rand_index");
    r.rand_index_preseg = Num(m, "rand_index_preseg");
    r.preseg_purity = Num(m, "preseg_purity");
    r.coverage_rate = Num(m, "coverage_rate");
    r.coverage_quality = Num(m, "coverage_quality");
    r.travel_m = Num(m, "travel_m");
    r.views = Int(m, "views");
    r.nbo_count = Int(m, "nbo_count");
    r.nbv_per_object = Num(m, "nbv_per_object");
    if (m.contains("per_category") && m["per_category"].is_object()) {
      for (const auto& [name, c] : m["per_category"].items()) {
        r.per_category[name] = {Int(c, "ground_truth"), Int(c, "outputs"), Int(c, "true_positives")};
      }
    }
    if (m.contains("instances") && m["instances"].is_array()) {
      // The label of the object holding most of each instance's points.
      std::map<int, std::pair<int, std::string>> largest;  // instance -> (points, label)
      if (j.contains("objects") && j["objects"].is_array()) {
        for (const Json& o : j["objects"]) {
          if (!o.is_object() || !o.contains("gt_instance") || !o["gt_instance"].is_number()) continue;
          const int points = Int(o, "points");
          auto& best = largest[o["gt_instance"].get<int>()];
          if (best.second.empty() || points > best.first) {
            best = {points, o.contains("category") && o["category"].is_string() ? o["category"].get<std::string>()
                                                                                 : std::string("unlabelled")};
          }
        }
      }
      for (const Json& i : m["instances"]) {
        if (!i.is_object()) continue;
        ReportedInstance c;
        c.category = i.value("category", std::string());
        c.surface_voxels = Int(i, "surface_voxels");
        c.visible_voxels = Int(i, "visible_voxels");
        c.matched = i.value("matched", false);
        auto it = i.contains("instance") && i["instance"].is_number() ? largest.find(i["instance"].get<int>())
                                                                       : largest.end();
        c.reported_as = it != largest.end() ? it->second.second : "not reported";
        r.instances.push_back(c);
      }
      AnalyseRunErrors(j, source, &r);
    }
    if (m.contains("reachable") && m["reachable"].is_object()) {
      r.has_reachable = true;
      r.ground_truth_reachable = Int(m["reachable"], "ground_truth_objects");
      r.recall_reachable = Num(m["reachable"], "recall");
      r.precision_reachable = Num(m["reachable"], "precision");
    }
    if (m.contains("never_seen") && m["never_seen"].is_array()) {
      for (const Json& o : m["never_seen"]) {
        if (o.is_object()) r.never_seen.push_back(o.value("name", std::string()) + " (" + o.value("category", std::string()) + ")");
      }
    }
    if (m.contains("unreachable_rooms") && m["unreachable_rooms"].is_array()) {
      for (const Json& u : m["unreachable_rooms"]) {
        if (!u.is_object()) continue;
        RunSummary::UnreachableRoomSummary room;
        room.room = Int(u, "room");
        room.area_m2 = Num(u, "area_m2");
        if (u.contains("objects") && u["objects"].is_array()) {
          for (const Json& o : u["objects"]) {
            if (o.is_object()) room.objects.push_back(o.value("name", std::string()) + " (" + o.value("category", std::string()) + ")");
          }
        }
        r.unreachable_rooms.push_back(room);
      }
    }
    if (m.contains("rand_index_per_view") && m["rand_index_per_view"].is_array()) {
      for (const Json& p : m["rand_index_per_view"]) {
        if (p.is_array() && p.size() >= 2 && p[0].is_number() && p[1].is_number()) {
          r.rand_index_per_view.emplace_back(p[0].get<int>(), p[1].get<double>());
        }
      }
    }
    if (m.contains("coverage_per_view") && m["coverage_per_view"].is_array()) {
      int view = 0;
      for (const Json& p : m["coverage_per_view"]) {
        CoveragePoint c;
        c.view = ++view;
        const std::size_t i = static_cast<std::size_t>(view - 1);
        c.travel_m = i < view_travel.size() ? view_travel[i] : travel;
        c.nbo_switch = i < view_nbo.size() && view_nbo[i];
        if (p.is_array() && p.size() >= 2 && p[0].is_number() && p[1].is_number()) {
          c.rate = p[0].get<double>();
          c.quality = p[1].get<double>();
        }
        r.coverage.push_back(c);
      }
    }
  } else {
    r.travel_m = travel;
    r.views = static_cast<int>(view_travel.size());
  }
  const Json& t = j["timing_s"];
  r.timing_s = {Num(t, "total"), Num(t, "sense"), Num(t, "fuse"), Num(t, "segment"),
                Num(t, "recognize"), Num(t, "nbo"), Num(t, "nbv"), Num(t, "navigate_sim")};
  if (j.contains("peak_rss_mb") && j["peak_rss_mb"].is_number()) r.peak_rss_mb = j["peak_rss_mb"].get<double>();
  if (j.contains("cpu_s") && j["cpu_s"].is_number()) r.cpu_s = j["cpu_s"].get<double>();
  return r;
}

namespace {

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Scene id and method of a run folder.
void NameRun(const fs::path& run_dir, std::string* scene_id, std::string* method) {
  const fs::path scene_dir = run_dir.parent_path();
  if (scene_dir.parent_path().filename() == "runs") {
    *scene_id = scene_dir.filename().string();
    *method = run_dir.filename().string();
  } else {
    *scene_id = run_dir.filename().string();
    *method = "ours";
  }
}

}  // namespace

namespace {

// Whether a run.json or failed.json lies below `dir` (report/ folders skipped, as CollectRuns does).
bool HoldsRun(const std::string& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    if (it->is_directory() && it->path().filename() == "report") {
      it.disable_recursion_pending();
      continue;
    }
    const std::string name = it->path().filename().string();
    if (it->is_regular_file() && (name == "run.json" || name == "failed.json")) return true;
  }
  if (ec) throw InputError(dir + ": cannot list: " + ec.message());
  return false;
}

}  // namespace

std::vector<std::string> FoldersWithoutRuns(const std::vector<std::string>& dirs) {
  std::vector<std::string> empty;
  for (const auto& dir : dirs) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw InputError(dir + ": folder not found");
    if (!HoldsRun(dir)) empty.push_back(dir);
  }
  return empty;
}

std::vector<RunSummary> CollectRuns(const std::vector<std::string>& dirs) {
  std::vector<fs::path> files;
  for (const auto& dir : dirs) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw InputError(dir + ": folder not found");
    for (auto it = fs::recursive_directory_iterator(dir, ec); it != fs::recursive_directory_iterator();
         it.increment(ec)) {
      if (ec) break;
      if (it->is_directory() && it->path().filename() == "report") {
        it.disable_recursion_pending();
        continue;
      }
      const std::string name = it->path().filename().string();
      if (it->is_regular_file() && (name == "run.json" || name == "failed.json")) files.push_back(it->path());
    }
    if (ec) throw InputError(dir + ": cannot list: " + ec.message());
  }
  std::sort(files.begin(), files.end());
  std::map<std::pair<std::string, std::string>, RunSummary> runs;
  for (const auto& file : files) {
    std::string scene_id, method;
    NameRun(file.parent_path(), &scene_id, &method);
    const auto key = std::make_pair(scene_id, method);
    if (file.filename() == "run.json") {
      const std::string text = ReadFile(file);
      // A run still being written has no run.json yet; an unparsable one is an error.
      RunSummary r = ParseRunJson(text, scene_id, method, file.string());
      auto it = runs.find(key);
      if (it == runs.end() || it->second.failed) runs[key] = std::move(r);
    } else {
      if (fs::exists(file.parent_path() / "run.json")) continue;  // finished on a later attempt
      if (runs.count(key)) continue;
      const Json j = Json::parse(ReadFile(file), nullptr, false);
      RunSummary r;
      r.scene_id = scene_id;
      r.method = method;
      r.failed = true;
      if (j.is_object()) {
        r.exit_code = Int(j, "exit_code");
        r.scene_spec = j.value("scene", std::string());
      }
      r.scene_category = SceneCategoryOfSpec(r.scene_spec);
      runs[key] = std::move(r);
    }
  }
  std::vector<RunSummary> out;
  for (auto& [key, r] : runs) out.push_back(std::move(r));
  return out;
}

namespace {

template <class T>
std::vector<std::string> Ordered(const std::set<std::string>& present, const std::vector<T>& canonical) {
  std::vector<std::string> out;
  for (const auto& c : canonical) {
    if (present.count(c)) out.push_back(c);
  }
  for (const auto& p : present) {
    if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  }
  return out;
}

SceneCategoryStats Aggregate(const std::string& category, const std::vector<const RunSummary*>& runs) {
  SceneCategoryStats s;
  s.category = category;
  int with_metrics = 0;
  for (const RunSummary* r : runs) {
    if (r->failed) {
      ++s.failed;
      continue;
    }
    ++s.scenes;
    s.timing_s.total += r->timing_s.total;
    s.timing_s.sense += r->timing_s.sense;
    s.timing_s.fuse += r->timing_s.fuse;
    s.timing_s.segment += r->timing_s.segment;
    s.timing_s.recognize += r->timing_s.recognize;
    s.timing_s.nbo += r->timing_s.nbo;
    s.timing_s.nbv += r->timing_s.nbv;
    s.timing_s.navigate_sim += r->timing_s.navigate_sim;
    s.travel_m += r->travel_m;
    s.views += r->views;
    if (r->cpu_s >= 0.0) {
      ++s.cpu_runs;
      s.cpu_s += r->cpu_s;
      s.cpu_s_max = std::max(s.cpu_s_max, r->cpu_s);
    }
    if (r->peak_rss_mb >= 0.0) {
      ++s.rss_runs;
      s.peak_rss_mb += r->peak_rss_mb;
      s.peak_rss_mb_max = std::max(s.peak_rss_mb_max, r->peak_rss_mb);
    }
    if (!r->has_metrics) continue;
    ++with_metrics;
    s.objects_per_scene += r->ground_truth_objects;
    s.recall += r->recall;
    s.precision += r->precision;
    s.recall_floor += r->recall_floor;
    s.precision_floor += r->precision_floor;
    s.rand_index += r->rand_index;
    s.rand_index_preseg += r->rand_index_preseg;
    s.coverage_rate += r->coverage_rate;
    s.coverage_quality += r->coverage_quality;
    s.nbo_count += r->nbo_count;
  }
  if (s.scenes > 0) {
    const double n = s.scenes;
    s.timing_s.total /= n;
    s.timing_s.sense /= n;
    s.timing_s.fuse /= n;
    s.timing_s.segment /= n;
    s.timing_s.recognize /= n;
    s.timing_s.nbo /= n;
    s.timing_s.nbv /= n;
    s.timing_s.navigate_sim /= n;
    s.travel_m /= n;
    s.views /= n;
  }
  if (s.cpu_runs > 0) s.cpu_s /= s.cpu_runs;
  if (s.rss_runs > 0) s.peak_rss_mb /= s.rss_runs;
  if (with_metrics > 0) {
    const double n = with_metrics;
    for (double* v : {&s.objects_per_scene, &s.recall, &s.precision, &s.recall_floor, &s.precision_floor,
                      &s.rand_index, &s.rand_index_preseg, &s.coverage_rate, &s.coverage_quality, &s.nbo_count}) {
      *v /= n;
    }
  }
  return s;
}

// Per-run shares of V_S by ground-truth category, averaged over the runs that have instances.
std::vector<CoverageBreakdownRow> CoverageBreakdown(const std::vector<const RunSummary*>& runs) {
  std::map<std::string, CoverageBreakdownRow> rows;
  std::map<std::string, std::map<std::string, double>> missed;
  int counted = 0;
  for (const RunSummary* r : runs) {
    double total = 0.0;
    for (const auto& i : r->instances) total += i.surface_voxels;
    if (!(total > 0.0)) continue;
    ++counted;
    for (const auto& i : r->instances) {
      CoverageBreakdownRow& row = rows[i.category];
      row.category = i.category;
      row.surface += i.surface_voxels / total;
      row.seen += i.visible_voxels / total;
      if (i.matched) {
        row.covered += i.visible_voxels / total;
      } else if (i.visible_voxels > 0) {
        missed[i.category][i.reported_as] += i.visible_voxels / total;
      }
    }
  }
  std::vector<CoverageBreakdownRow> out;
  for (auto& [name, row] : rows) {
    row.surface /= counted;
    row.seen /= counted;
    row.covered /= counted;
    for (const auto& [label, share] : missed[name]) row.missed_as.emplace_back(label, share / counted);
    std::stable_sort(row.missed_as.begin(), row.missed_as.end(),
                     [](const auto& a, const auto& b) { return a.second > b.second; });
    out.push_back(std::move(row));
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const CoverageBreakdownRow& a, const CoverageBreakdownRow& b) { return a.surface > b.surface; });
  return out;
}

}  // namespace

Report BuildReport(std::vector<RunSummary> runs) {
  std::sort(runs.begin(), runs.end(), [](const RunSummary& a, const RunSummary& b) {
    return std::tie(a.scene_id, a.method) < std::tie(b.scene_id, b.method);
  });
  Report report;
  report.runs = std::move(runs);
  std::set<std::string> methods, categories;
  for (const auto& r : report.runs) {
    methods.insert(r.method);
    categories.insert(r.scene_category);
    (r.failed ? report.failed_runs : report.complete_runs)++;
  }
  std::vector<std::string> method_order;
  for (const auto& m : AllBenchMethods()) method_order.push_back(m.name);
  report.methods = Ordered(methods, method_order);
  report.scene_categories = Ordered(categories, SceneCategories());
  for (const auto& m : report.methods) {
    auto& rows = report.by_method[m];
    for (const auto& c : report.scene_categories) rows.push_back(Aggregate(c, Select(report, m, c, false)));
    rows.push_back(Aggregate("all", Select(report, m, "all", false)));
  }
  // Table 2: object categories of the runs of "ours", summed.
  std::map<std::string, CategoryCounts> sums;
  for (const RunSummary* r : Select(report, "ours", "all", true)) {
    for (const auto& [name, c] : r->per_category) {
      auto& s = sums[name];
      s.ground_truth += c.ground_truth;
      s.outputs += c.outputs;
      s.true_positives += c.true_positives;
    }
  }
  std::set<std::string> object_names;
  for (const auto& [name, c] : sums) object_names.insert(name);
  std::vector<std::string> paper_order;
  for (const auto& row : PaperTable2()) paper_order.push_back(row.category);
  for (const auto& name : Ordered(object_names, paper_order)) {
    ObjectCategoryStats o;
    o.category = name;
    o.counts = sums[name];
    o.recall = o.counts.ground_truth > 0 ? double(o.counts.true_positives) / o.counts.ground_truth : 0.0;
    o.precision = o.counts.outputs > 0 ? double(o.counts.true_positives) / o.counts.outputs : 0.0;
    report.object_categories.push_back(o);
  }
  report.coverage_breakdown = CoverageBreakdown(Select(report, "ours", "all", true));
  // Error classes and confusion matrices: summed counts (so shares weigh each reported object the
  // same, unlike the per-scene means of Table 1).
  MethodErrors all;
  all.method = "all";
  for (const auto& m : report.methods) {
    MethodErrors e;
    e.method = m;
    for (const RunSummary* r : Select(report, m, "all", true)) {
      if (!r->has_error_analysis) continue;
      ++e.runs;
      e.breakdown.Add(r->errors);
      e.confusion.Add(r->confusion);
    }
    if (e.runs == 0) continue;
    all.runs += e.runs;
    all.breakdown.Add(e.breakdown);
    all.confusion.Add(e.confusion);
    report.errors.push_back(std::move(e));
  }
  if (all.runs > 0) report.errors.push_back(std::move(all));
  return report;
}

Curve MeanCoverageOverViews(const std::vector<const RunSummary*>& runs, bool quality) {
  Curve curve;
  std::size_t max_views = 0;
  int n = 0;
  for (const RunSummary* r : runs) {
    if (r->coverage.empty()) continue;
    max_views = std::max(max_views, r->coverage.size());
    ++n;
  }
  for (std::size_t v = 0; v < max_views; ++v) {
    double sum = 0.0;
    for (const RunSummary* r : runs) {
      if (r->coverage.empty()) continue;
      const CoveragePoint& p = r->coverage[std::min(v, r->coverage.size() - 1)];
      sum += quality ? p.quality : p.rate;
    }
    curve.x.push_back(static_cast<double>(v + 1));
    curve.y.push_back(sum / n);
  }
  return curve;
}

Curve MeanCoverageOverTravel(const std::vector<const RunSummary*>& runs, int samples, bool quality) {
  Curve curve;
  double max_travel = 0.0;
  int n = 0;
  for (const RunSummary* r : runs) {
    if (r->coverage.empty()) continue;
    max_travel = std::max(max_travel, r->coverage.back().travel_m);
    ++n;
  }
  if (n == 0) return curve;
  samples = std::max(2, samples);
  for (int i = 0; i < samples; ++i) {
    const double x = max_travel * i / (samples - 1);
    double sum = 0.0;
    for (const RunSummary* r : runs) {
      if (r->coverage.empty()) continue;
      double value = 0.0;  // nothing seen before the first view
      for (const auto& p : r->coverage) {
        if (p.travel_m > x + 1e-9) break;
        value = quality ? p.quality : p.rate;
      }
      sum += value;
    }
    curve.x.push_back(x);
    curve.y.push_back(sum / n);
  }
  return curve;
}

Curve MeanQualityOverNbos(const std::vector<const RunSummary*>& runs) {
  // Per run: quality just before each switch to a next best object, and at the end.
  std::vector<std::vector<double>> per_run;
  std::size_t longest = 0;
  for (const RunSummary* r : runs) {
    if (r->coverage.empty()) continue;
    std::vector<double> q;
    double last = 0.0;
    for (const auto& p : r->coverage) {
      if (p.nbo_switch) q.push_back(last);
      last = p.quality;
    }
    q.push_back(last);
    longest = std::max(longest, q.size());
    per_run.push_back(std::move(q));
  }
  Curve curve;
  for (std::size_t k = 0; k < longest; ++k) {
    double sum = 0.0;
    for (const auto& q : per_run) sum += q[std::min(k, q.size() - 1)];
    curve.x.push_back(static_cast<double>(k));
    curve.y.push_back(sum / per_run.size());
  }
  return curve;
}

namespace report_internal {

std::vector<const RunSummary*> Select(const Report& report, const std::string& method, const std::string& category,
                                      bool complete_only) {
  std::vector<const RunSummary*> out;
  for (const auto& r : report.runs) {
    if (r.method != method) continue;
    if (category != "all" && r.scene_category != category) continue;
    if (complete_only && (r.failed || !r.has_metrics)) continue;
    out.push_back(&r);
  }
  return out;
}

const SceneCategoryStats* Stats(const Report& report, const std::string& method, const std::string& category) {
  auto it = report.by_method.find(method);
  if (it == report.by_method.end()) return nullptr;
  for (const auto& s : it->second) {
    if (s.category == category) return s.scenes > 0 ? &s : nullptr;
  }
  return nullptr;
}

bool Has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

const PaperSceneRow* PaperScene(const std::string& category) {
  for (const auto& row : PaperTable1()) {
    if (category == row.category) return &row;
  }
  return nullptr;
}
const PaperObjectRow* PaperObject(const std::string& category) {
  for (const auto& row : PaperTable2()) {
    if (category == row.category) return &row;
  }
  return nullptr;
}
const PaperTimingRow* PaperTiming(const std::string& category) {
  for (const auto& row : PaperTable3()) {
    if (category == row.category) return &row;
  }
  return nullptr;
}

// The first complete run of "ours" in a scene category (by scene id): Fig. 11 shows one scene each.
const RunSummary* ExampleRun(const Report& report, const std::string& category) {
  for (const RunSummary* r : Select(report, "ours", category, true)) {
    if (!r->coverage.empty()) return r;
  }
  return nullptr;
}

const std::vector<std::string>& AblationMethods() {
  static const std::vector<std::string> kMethods = {"ours", "no-objectness", "no-size", "no-distance",
                                                    "no-orientation", "frontier"};
  return kMethods;
}

// The errors of the methods alone (without "all"), and the "all" entry (null when there is none).
std::vector<const MethodErrors*> ErrorsPerMethod(const Report& report) {
  std::vector<const MethodErrors*> out;
  for (const auto& e : report.errors) {
    if (e.method != "all") out.push_back(&e);
  }
  return out;
}
const MethodErrors* ErrorsOverall(const Report& report) {
  for (const auto& e : report.errors) {
    if (e.method == "all") return &e;
  }
  return nullptr;
}

}  // namespace report_internal

}  // namespace objscan::eval
