#include "objscan/eval/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "objscan/common/error.h"
#include "objscan/eval/benchmark.h"
#include "objscan/eval/plot.h"
#include "objscan/io/atomic_file.h"
#include "objscan/scanning/system_config.h"
#include "objscan/world/category.h"
#include "objscan/world/scene.h"

namespace objscan::eval {
namespace fs = std::filesystem;
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

namespace {

Json TimingJson(const RunTiming& t) {
  return Json{{"total", t.total}, {"sense", t.sense}, {"fuse", t.fuse}, {"segment", t.segment},
              {"recognize", t.recognize}, {"nbo", t.nbo}, {"nbv", t.nbv}, {"navigate_sim", t.navigate_sim}};
}

Json StatsJson(const SceneCategoryStats& s) {
  return Json{{"category", s.category},
              {"scenes", s.scenes},
              {"failed", s.failed},
              {"objects_per_scene", s.objects_per_scene},
              {"recall", s.recall},
              {"precision", s.precision},
              {"recall_floor", s.recall_floor},
              {"precision_floor", s.precision_floor},
              {"rand_index", s.rand_index},
              {"rand_index_preseg", s.rand_index_preseg},
              {"coverage_rate", s.coverage_rate},
              {"coverage_quality", s.coverage_quality},
              {"travel_m", s.travel_m},
              {"views", s.views},
              {"nbo_count", s.nbo_count},
              {"timing_s", TimingJson(s.timing_s)},
              {"resources", Json{{"cpu_runs", s.cpu_runs},
                                 {"cpu_s", s.cpu_s},
                                 {"cpu_s_max", s.cpu_s_max},
                                 {"rss_runs", s.rss_runs},
                                 {"peak_rss_mb", s.peak_rss_mb},
                                 {"peak_rss_mb_max", s.peak_rss_mb_max}}}};
}

Json CurveJson(const Curve& c) { return Json{{"x", c.x}, {"y", c.y}}; }

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

Json BreakdownJson(const ErrorBreakdown& b) {
  Json counts = Json::object(), shares = Json::object();
  for (OutputOutcome o : OutputOutcomesInReportOrder()) {
    counts[OutputOutcomeName(o)] = b.Count(o);
    shares[OutputOutcomeName(o)] = b.Share(o);
  }
  Json j{{"reported", b.Total()}, {"counts", counts}, {"shares", shares}};
  if (b.share_known > 0) {
    Json on_piece = Json::object();
    for (OutputOutcome o : OutputOutcomesInReportOrder()) on_piece[OutputOutcomeName(o)] = b.OnPiece(o);
    j["share_known"] = b.share_known;
    j["on_piece"] = on_piece;
  }
  return j;
}

Json ConfusionJson(const ConfusionMatrix& m) {
  const std::vector<std::string> rows = m.Rows(), columns = m.Columns();
  Json counts = Json::array();
  for (const auto& row : rows) {
    Json line = Json::array();
    for (const auto& column : columns) line.push_back(m.Count(row, column));
    counts.push_back(line);
  }
  return Json{{"rows", rows}, {"columns", columns}, {"counts", counts}};
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

Json ReportedObjects(const Report& report) {
  Json classes = Json::array();
  for (OutputOutcome o : OutputOutcomesInReportOrder()) classes.push_back(OutputOutcomeName(o));
  Json by_method = Json::array();
  for (const MethodErrors* e : ErrorsPerMethod(report)) {
    Json row{{"method", e->method}, {"runs", e->runs}};
    row.update(BreakdownJson(e->breakdown));
    by_method.push_back(row);
  }
  Json overall = nullptr;
  if (const MethodErrors* e = ErrorsOverall(report)) {
    overall = Json{{"runs", e->runs}};
    overall.update(BreakdownJson(e->breakdown));
  }
  return Json{{"classes", classes}, {"by_method", by_method}, {"overall", overall}};
}

}  // namespace

std::string ReportedObjectsJson(const Report& report) { return ReportedObjects(report).dump(2) + "\n"; }

std::string ConfusionCsv(const Report& report) {
  const MethodErrors* overall = ErrorsOverall(report);
  if (overall == nullptr) return std::string();
  // One header for every method: the columns of the sum of all matrices.
  const std::vector<std::string> columns = overall->confusion.Columns();
  std::ostringstream csv;
  csv << "method,ground_truth";
  for (const auto& c : columns) csv << ',' << c;
  csv << ",total\n";
  std::vector<const MethodErrors*> written = ErrorsPerMethod(report);
  if (written.size() > 1) written.push_back(overall);
  for (const MethodErrors* e : written) {
    for (const auto& row : e->confusion.Rows()) {
      csv << e->method << ',' << row;
      for (const auto& c : columns) csv << ',' << e->confusion.Count(row, c);
      csv << ',' << e->confusion.RowTotal(row) << '\n';
    }
  }
  return csv.str();
}

std::string ReportJson(const Report& report) {
  Json j;
  j["runs"] = Json{{"complete", report.complete_runs}, {"failed", report.failed_runs}};
  j["methods"] = report.methods;
  j["scene_categories"] = report.scene_categories;
  // Table 1.
  Json table1 = Json::array();
  if (report.by_method.count("ours")) {
    for (const auto& s : report.by_method.at("ours")) {
      Json row = StatsJson(s);
      if (const PaperSceneRow* p = PaperScene(s.category)) {
        row["paper"] = Json{{"scenes", p->scenes},
                            {"objects_per_scene", p->objects_per_scene},
                            {"recall", p->recall_pct / 100},
                            {"precision", p->precision_pct / 100},
                            {"recall_floor", p->recall_floor_pct / 100},
                            {"precision_floor", p->precision_floor_pct / 100}};
      } else if (s.category == "all") {
        // The paper's text: 104 scenes, average recall 65.93 % and precision 70.61 %.
        row["paper"] = Json{{"scenes", 104}, {"recall", 0.6593}, {"precision", 0.7061}};
      }
      table1.push_back(row);
    }
  }
  j["table1"] = table1;
  // The runs that could not reach every room, frontier or object (the markdown's section of that name).
  Json unreachable = Json::array();
  for (const auto& r : report.runs) {
    if (r.failed || !r.ReachedLess()) continue;
    Json rooms = Json::array();
    for (const auto& u : r.unreachable_rooms) {
      rooms.push_back(Json{{"room", u.room}, {"area_m2", u.area_m2}, {"objects", u.objects}});
    }
    Json entry{{"scene", r.scene_id},
               {"method", r.method},
               {"terminated", r.terminated},
               {"rooms", rooms},
               {"frontiers", r.unreachable_frontiers},
               {"frontier_area_m2", r.unreachable_frontier_area_m2},
               {"objects_left", r.objects_left},
               {"never_seen", r.never_seen}};
    if (r.has_reachable) {
      entry["reachable"] = Json{{"ground_truth_objects", r.ground_truth_reachable},
                                {"recall", r.recall_reachable},
                                {"precision", r.precision_reachable}};
    }
    unreachable.push_back(entry);
  }
  j["unreachable"] = unreachable;
  // Table 2.
  Json table2 = Json::array();
  for (const auto& o : report.object_categories) {
    Json row{{"category", o.category},
             {"ground_truth", o.counts.ground_truth},
             {"outputs", o.counts.outputs},
             {"true_positives", o.counts.true_positives},
             {"recall", o.recall},
             {"precision", o.precision}};
    if (const PaperObjectRow* p = PaperObject(o.category)) {
      row["paper"] = Json{{"objects", p->objects}, {"recall", p->recall_pct / 100}, {"precision", p->precision_pct / 100}};
    }
    table2.push_back(row);
  }
  j["table2"] = table2;
  Json breakdown = Json::array();
  for (const auto& row : report.coverage_breakdown) {
    Json missed = Json::array();
    for (const auto& [label, share] : row.missed_as) missed.push_back(Json{{"reported_as", label}, {"share", share}});
    breakdown.push_back(Json{{"category", row.category},
                             {"surface", row.surface},
                             {"seen", row.seen},
                             {"covered", row.covered},
                             {"seen_not_recognized", missed}});
  }
  j["coverage_breakdown"] = breakdown;
  if (!report.errors.empty()) {
    j["reported_objects"] = ReportedObjects(report);
    Json confusion = Json::object();
    for (const auto& e : report.errors) confusion[e.method] = ConfusionJson(e.confusion);
    j["confusion"] = confusion;
  }
  // Table 3 (seconds for ours, minutes for the paper).
  Json table3 = Json::array();
  if (report.by_method.count("ours")) {
    for (const auto& s : report.by_method.at("ours")) {
      if (s.scenes == 0) continue;
      Json row{{"category", s.category},
               {"ours_s",
                Json{{"total_with_navigation", s.timing_s.total + s.timing_s.navigate_sim},
                     {"compute", s.timing_s.total},
                     {"navigate_sim", s.timing_s.navigate_sim},
                     {"segment", s.timing_s.segment},
                     {"recognize", s.timing_s.recognize},
                     {"nbo", s.timing_s.nbo},
                     {"nbv", s.timing_s.nbv}}}};
      if (const PaperTimingRow* p = PaperTiming(s.category)) {
        row["paper_min"] = Json{{"total", p->total_min},     {"navigate", p->navigate_min}, {"segment", p->segment_min},
                                {"nbo", p->nbo_min},         {"nbv", p->nbv_min}};
      }
      table3.push_back(row);
    }
  }
  j["table3"] = table3;
  Json methods = Json::object();
  for (const auto& m : report.methods) {
    Json rows = Json::array();
    for (const auto& s : report.by_method.at(m)) rows.push_back(StatsJson(s));
    methods[m] = rows;
  }
  j["by_method"] = methods;
  // Fig. 10a.
  Json fig10a = Json::object();
  for (const auto& c : report.scene_categories) {
    Json row = Json::object();
    if (const auto* s = Stats(report, "ours", c)) {
      row["ours"] = s->rand_index;
      row["ours_presegmentation"] = s->rand_index_preseg;
    }
    if (const auto* s = Stats(report, "preseg-only", c)) row["preseg_only"] = s->rand_index;
    fig10a[c] = row;
  }
  j["rand_index"] = fig10a;
  // Curves.
  Json fig11 = Json::object();
  for (const auto& c : report.scene_categories) {
    const auto runs = Select(report, "ours", c, true);
    if (runs.empty()) continue;
    fig11[c] = Json{{"rate", CurveJson(MeanCoverageOverViews(runs, false))},
                    {"quality", CurveJson(MeanCoverageOverViews(runs, true))}};
  }
  j["coverage_over_views"] = fig11;
  Json fig13 = Json::object(), fig13b = Json::object();
  for (const auto& m : report.methods) {
    const auto runs = Select(report, m, "all", true);
    if (runs.empty()) continue;
    fig13[m] = CurveJson(MeanCoverageOverTravel(runs, 41, false));
    fig13b[m] = CurveJson(MeanQualityOverNbos(runs));
  }
  j["coverage_rate_over_travel"] = fig13;
  j["coverage_quality_over_nbos"] = fig13b;
  Json per_run = Json::array();
  for (const auto& r : report.runs) {
    Json row{{"scene", r.scene_id}, {"method", r.method}, {"category", r.scene_category}, {"failed", r.failed}};
    if (r.failed) {
      row["exit_code"] = r.exit_code;
    } else {
      row["terminated"] = r.terminated;
      row["steps"] = r.steps;
      row["views"] = r.views;
      row["travel_m"] = r.travel_m;
      row["recall"] = r.recall;
      row["precision"] = r.precision;
      row["rand_index"] = r.rand_index;
      row["coverage_rate"] = r.coverage_rate;
      row["coverage_quality"] = r.coverage_quality;
      row["compute_s"] = r.timing_s.total;
      if (r.cpu_s >= 0.0) row["cpu_s"] = r.cpu_s;
      if (r.peak_rss_mb >= 0.0) row["peak_rss_mb"] = r.peak_rss_mb;
      if (r.has_error_analysis) row["reported_objects"] = BreakdownJson(r.errors);
    }
    per_run.push_back(row);
  }
  j["per_run"] = per_run;
  return j.dump(2) + "\n";
}

namespace {

std::string Pct(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.2f%%", 100.0 * v);
  return buf;
}
std::string Fix(double v, int decimals) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}
// The first cell of an error-class table's row: the method, or "All methods" in bold.
std::string ErrorsRowLabel(const MethodErrors& e) {
  return e.method == "all" ? std::string("**All methods**") : "`" + e.method + "`";
}
std::string OutcomeLabel(OutputOutcome outcome) {
  switch (outcome) {
    case OutputOutcome::kCorrect: return "correct";
    case OutputOutcome::kWrongCategory: return "wrong category";
    case OutputOutcome::kDuplicatePiece: return "duplicate piece";
    case OutputOutcome::kOtherObject: return "`other` object";
    case OutputOutcome::kBackgroundOrStructure: return "background or structure";
  }
  return OutputOutcomeName(outcome);
}
std::string Label(const std::string& category) {
  if (category == "all") return "**All**";
  std::string s = category;
  std::replace(s.begin(), s.end(), '_', ' ');
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

}  // namespace

std::string ReportMarkdown(const Report& report) {
  std::ostringstream md;
  md << "# objscan benchmark report\n\n";
  md << report.complete_runs << " complete runs, " << report.failed_runs << " failed; methods: ";
  for (std::size_t i = 0; i < report.methods.size(); ++i) md << (i ? ", " : "") << "`" << report.methods[i] << "`";
  md << ".\nMeans are over scenes (each run weighs the same). Paper figures: Liu et al. 2018, Tables 1-3 "
        "(their 104-scene SUNCG/ScanNet set, not these scenes).\n\n";

  md << "## Table 1: object recognition per scene category (`ours`)\n\n";
  md << "| Category | #S | #O | Recall | Precision | Recall(G) | Precision(G) | paper #S | paper #O | paper Recall | "
        "paper Precision | paper Recall(G) | paper Precision(G) |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  if (report.by_method.count("ours")) {
    for (const auto& s : report.by_method.at("ours")) {
      md << "| " << Label(s.category) << " | " << s.scenes << (s.failed ? " (+" + std::to_string(s.failed) + " failed)" : "")
         << " | ";
      if (s.scenes > 0) {
        md << Fix(s.objects_per_scene, 1) << " | " << Pct(s.recall) << " | " << Pct(s.precision) << " | "
           << Pct(s.recall_floor) << " | " << Pct(s.precision_floor) << " | ";
      } else {
        md << "- | - | - | - | - | ";
      }
      if (const PaperSceneRow* p = PaperScene(s.category)) {
        md << p->scenes << " | " << p->objects_per_scene << " | " << Fix(p->recall_pct, 2) << "% | "
           << Fix(p->precision_pct, 2) << "% | " << Fix(p->recall_floor_pct, 2) << "% | "
           << Fix(p->precision_floor_pct, 2) << "% |\n";
      } else if (s.category == "all") {
        md << "104 | | 65.93% | 70.61% | | |\n";
      } else {
        md << " | | | | | |\n";
      }
    }
  }
  md << "\n## Methods compared (all scenes)\n\n";
  md << "| Method | runs | failed | Recall | Precision | Rand Index | Coverage rate | Coverage quality | Travel m | "
        "Views | NBOs | Compute s |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& m : report.methods) {
    const SceneCategoryStats& s = report.by_method.at(m).back();
    md << "| `" << m << "` | " << s.scenes << " | " << s.failed << " | " << Pct(s.recall) << " | "
       << Pct(s.precision) << " | " << Fix(s.rand_index, 3) << " | " << Pct(s.coverage_rate) << " | "
       << Pct(s.coverage_quality) << " | " << Fix(s.travel_m, 1) << " | " << Fix(s.views, 1) << " | "
       << Fix(s.nbo_count, 1) << " | " << Fix(s.timing_s.total, 1) << " |\n";
  }

  md << "\n## Resources per method (all scenes)\n\n";
  md << "Per run of `objscan run` (one process each): CPU time is user + system over all threads (database "
        "loading and evaluation included), compute the wall time of the method, peak RSS the most resident "
        "memory the process held. Runs whose run.json predates these fields are not counted.\n\n";
  md << "| Method | runs | CPU s mean | CPU s max | compute s mean | peak RSS MB mean | peak RSS MB max |\n";
  md << "|---|---|---|---|---|---|---|\n";
  for (const auto& m : report.methods) {
    const SceneCategoryStats& s = report.by_method.at(m).back();
    md << "| `" << m << "` | " << s.scenes << " | " << (s.cpu_runs ? Fix(s.cpu_s, 1) : "-") << " | "
       << (s.cpu_runs ? Fix(s.cpu_s_max, 1) : "-") << " | " << Fix(s.timing_s.total, 1) << " | "
       << (s.rss_runs ? Fix(s.peak_rss_mb, 0) : "-") << " | " << (s.rss_runs ? Fix(s.peak_rss_mb_max, 0) : "-")
       << " |\n";
  }

  md << "\n## Table 2: object recognition per object category (`ours`, summed over scenes)\n\n";
  md << "| Category | #O | outputs | TP | Recall | Precision | paper #O | paper Recall | paper Precision |\n";
  md << "|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& o : report.object_categories) {
    md << "| " << Label(o.category) << " | " << o.counts.ground_truth << " | " << o.counts.outputs << " | "
       << o.counts.true_positives << " | " << (o.counts.ground_truth ? Pct(o.recall) : "-") << " | "
       << (o.counts.outputs ? Pct(o.precision) : "-") << " | ";
    if (const PaperObjectRow* p = PaperObject(o.category)) {
      md << p->objects << " | " << Fix(p->recall_pct, 2) << "% | " << Fix(p->precision_pct, 2) << "% |\n";
    } else {
      md << " | | |\n";
    }
  }

  if (!report.errors.empty()) {
    md << "\n## Where the reported objects go wrong (summed over runs)\n\n";
    md << "Every reported labelled object (an output of recall and precision) in exactly one class: correct (a "
          "true positive, precision's numerator: the right category on a ground-truth object no earlier output "
          "matched); wrong category (on an unmatched object of another category); duplicate piece (on an object "
          "another output matched); `other` object (on an unmatched object of category `other`); background or "
          "structure (on no ground-truth object). Counts summed over the runs, shares of the reported objects, so "
          "the correct share is the pooled precision, not Table 1's mean over scenes.\n\n";
    md << "| Method | runs | reported |";
    for (OutputOutcome o : OutputOutcomesInReportOrder()) md << ' ' << OutcomeLabel(o) << " |";
    md << "\n|---|---|---|";
    for (std::size_t k = 0; k < OutputOutcomesInReportOrder().size(); ++k) md << "---|";
    md << '\n';
    std::vector<const MethodErrors*> rows = ErrorsPerMethod(report);
    if (rows.size() > 1) rows.push_back(ErrorsOverall(report));
    for (const MethodErrors* e : rows) {
      md << "| " << ErrorsRowLabel(*e) << " | " << e->runs
         << " | " << e->breakdown.Total() << " |";
      for (OutputOutcome o : OutputOutcomesInReportOrder()) {
        md << ' ' << e->breakdown.Count(o) << " (" << Pct(e->breakdown.Share(o)) << ") |";
      }
      md << '\n';
    }
    bool any_share = false;
    for (const MethodErrors* e : rows) any_share = any_share || e->breakdown.share_known > 0;
    if (any_share) {
      md << "\nOn a piece: of each class, the reported objects holding less than half of their ground-truth "
            "object's reconstructed surface (the rest of it unlabelled or in other objects); counted over the "
            "reported objects whose run records that share (`gt_instance_share` in run.json).\n\n";
      md << "| Method | share known |";
      for (OutputOutcome o : OutputOutcomesInReportOrder()) {
        if (o != OutputOutcome::kBackgroundOrStructure) md << ' ' << OutcomeLabel(o) << ", on a piece |";
      }
      md << "\n|---|---|";
      for (std::size_t k = 1; k < OutputOutcomesInReportOrder().size(); ++k) md << "---|";
      md << '\n';
      for (const MethodErrors* e : rows) {
        md << "| " << ErrorsRowLabel(*e) << " | "
           << e->breakdown.share_known << " |";
        for (OutputOutcome o : OutputOutcomesInReportOrder()) {
          if (o != OutputOutcome::kBackgroundOrStructure) md << ' ' << e->breakdown.OnPiece(o) << " |";
        }
        md << '\n';
      }
    }
    // The matrix of "ours" (the method the report is about), else of the first method.
    const MethodErrors* shown = rows.front();
    for (const MethodErrors* e : rows) {
      if (e->method == "ours") shown = e;
    }
    const ConfusionMatrix& m = shown->confusion;
    const std::vector<std::string> columns = m.Columns();
    md << "\n## Confusion matrix (`" << shown->method << "`, summed over runs; every method in confusion.csv)\n\n";
    md << "Rows: the ground-truth category of the object a reported object lies on (its majority instance; "
          "background/structure when none). Columns: the reported category; missed counts the ground-truth "
          "objects no reported object lies on. A ground-truth object with two reported pieces counts twice in its "
          "row.\n\n";
    md << "| ground truth \\ reported |";
    for (const auto& c : columns) md << ' ' << Label(c) << " |";
    md << " total |\n|---|";
    for (std::size_t k = 0; k <= columns.size(); ++k) md << "---|";
    md << '\n';
    for (const auto& row : m.Rows()) {
      md << "| " << Label(row) << " |";
      for (const auto& c : columns) {
        const int n = m.Count(row, c);
        // The diagonal in bold, zeros left blank so the errors stand out.
        if (n == 0) {
          md << "  |";
        } else if (row == c) {
          md << " **" << n << "** |";
        } else {
          md << ' ' << n << " |";
        }
      }
      md << ' ' << m.RowTotal(row) << " |\n";
    }
    md << "| total |";
    for (const auto& c : columns) md << ' ' << m.ColumnTotal(c) << " |";
    md << " |\n";
  }

  if (!report.coverage_breakdown.empty()) {
    md << "\n## Where the coverage goes (`ours`, points of the mean coverage rate)\n\n";
    md << "Shares of V_S (the ground-truth object surface of the coverage rate) per ground-truth category, "
          "averaged over the runs like `coverage_rate`. Seen: within the valid range; covered: seen and on a "
          "matched object (summed over the rows, the coverage rate). The seen surface of unmatched instances is "
          "listed by what they were reported as: the label of the output object holding most of their points.\n\n";
    md << "| Category | share of V_S | seen | covered | seen, not recognized | reported as |\n";
    md << "|---|---|---|---|---|---|\n";
    double surface = 0, seen = 0, covered = 0;
    for (const auto& row : report.coverage_breakdown) {
      surface += row.surface;
      seen += row.seen;
      covered += row.covered;
      std::string as;
      for (std::size_t k = 0; k < row.missed_as.size() && k < 3; ++k) {
        as += (k ? ", " : "") + Label(row.missed_as[k].first) + " " + Fix(100.0 * row.missed_as[k].second, 2);
      }
      md << "| " << Label(row.category) << " | " << Fix(100.0 * row.surface, 2) << " | " << Fix(100.0 * row.seen, 2)
         << " | " << Fix(100.0 * row.covered, 2) << " | " << Fix(100.0 * (row.seen - row.covered), 2) << " | " << as
         << " |\n";
    }
    md << "| **All** | " << Fix(100.0 * surface, 2) << " | " << Fix(100.0 * seen, 2) << " | " << Fix(100.0 * covered, 2)
       << " | " << Fix(100.0 * (seen - covered), 2) << " | |\n";
  }

  md << "\n## Fig. 10a: Rand Index per scene category\n\n";
  md << "| Category | ours | preseg-only (Tateno) | pre-segmentation of ours |\n|---|---|---|---|\n";
  for (const auto& c : report.scene_categories) {
    const auto* o = Stats(report, "ours", c);
    const auto* p = Stats(report, "preseg-only", c);
    md << "| " << Label(c) << " | " << (o ? Fix(o->rand_index, 3) : "-") << " | " << (p ? Fix(p->rand_index, 3) : "-")
       << " | " << (o ? Fix(o->rand_index_preseg, 3) : "-") << " |\n";
  }
  md << "\nFig. 10b (`fig10b_rand_index_views`): the Rand Index of the segmentation after each analysis "
        "against the number of views seen, averaged over the runs of each method (a run counts at a view once it "
        "has been analysed there or before; runs without per-view data fall back to one dot at termination).\n";

  md << "\n## Table 3: running time per scene category (`ours`)\n\n";
  md << "Ours in seconds: compute is the wall time of the method; navigation is the simulated robot's driving "
        "time (not wall time); segment is pre-segmentation + graph cuts, recognize the database matching "
        "(the paper counts matching inside its Segment column). Paper in minutes (Gazebo + real robot "
        "timing).\n\n";
  md << "| Category | total (compute + nav) s | compute s | navigate (sim) s | segment s | recognize s | NBO s | NBV s | "
        "paper total min | paper navigate min | paper segment min | paper NBO min | paper NBV min |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  if (report.by_method.count("ours")) {
    for (const auto& s : report.by_method.at("ours")) {
      if (s.scenes == 0) continue;
      const RunTiming& t = s.timing_s;
      md << "| " << Label(s.category) << " | " << Fix(t.total + t.navigate_sim, 1) << " | " << Fix(t.total, 1) << " | "
         << Fix(t.navigate_sim, 1) << " | " << Fix(t.segment, 2) << " | " << Fix(t.recognize, 1) << " | "
         << Fix(t.nbo, 3) << " | " << Fix(t.nbv, 2) << " | ";
      if (const PaperTimingRow* p = PaperTiming(s.category)) {
        md << Fix(p->total_min, 1) << " | " << Fix(p->navigate_min, 1) << " | " << Fix(p->segment_min, 1) << " | "
           << Fix(p->nbo_min, 1) << " | " << Fix(p->nbv_min, 1) << " |\n";
      } else {
        md << " | | | | |\n";
      }
    }
  }
  if (Has(report.methods, "db-no-parts")) {
    md << "\n## Fig. 14: database with and without component/pair entries\n\n";
    md << "| Category | recall ours | recall db-no-parts | precision ours | precision db-no-parts |\n|---|---|---|---|---|\n";
    for (const auto& c : report.scene_categories) {
      const auto* o = Stats(report, "ours", c);
      const auto* p = Stats(report, "db-no-parts", c);
      md << "| " << Label(c) << " | " << (o ? Pct(o->recall) : "-") << " | " << (p ? Pct(p->recall) : "-") << " | "
         << (o ? Pct(o->precision) : "-") << " | " << (p ? Pct(p->precision) : "-") << " |\n";
    }
  }
  md << "\n## Runs\n\n| Scene | Method | terminated | steps | views | travel m | recall | precision | RI | "
        "coverage | compute s | reported: correct / wrong / duplicate / other / background |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : report.runs) {
    if (r.failed) {
      md << "| " << r.scene_id << " | `" << r.method << "` | **failed** (exit " << r.exit_code
         << ", see stderr.txt) | | | | | | | | | |\n";
      continue;
    }
    md << "| " << r.scene_id << " | `" << r.method << "` | " << r.terminated << " | " << r.steps << " | " << r.views
       << " | " << Fix(r.travel_m, 1) << " | " << Pct(r.recall) << " | " << Pct(r.precision) << " | "
       << Fix(r.rand_index, 3) << " | " << Pct(r.coverage_rate) << " | " << Fix(r.timing_s.total, 1) << " | ";
    if (r.has_error_analysis) {
      md << r.errors.Total() << ": ";
      for (OutputOutcome o : OutputOutcomesInReportOrder()) {
        md << (o == OutputOutcome::kCorrect ? "" : " / ") << r.errors.Count(o);
      }
    }
    md << " |\n";
  }
  if (std::any_of(report.runs.begin(), report.runs.end(), [](const RunSummary& r) { return r.ReachedLess(); })) {
    // Said apart so that a run's totals are not read as the robot's failure where it could not go.
    md << "\n## What the runs could not reach\n\n"
          "Rooms the robot could not drive into from its start (ground truth: closed doors, gaps narrower than the "
          "robot) with their objects, recall and precision over the other rooms, and what its own map left out of "
          "reach at the end (floor frontiers no path reaches, objects no reachable view shows), beside the objects "
          "of reachable rooms it never saw.\n\n"
          "| Scene | Method | terminated | unreachable rooms (objects) | recall / precision over reachable rooms | "
          "unreachable frontiers | objects left | never seen (reachable) |\n|---|---|---|---|---|---|---|---|\n";
    for (const auto& r : report.runs) {
      if (r.failed || !r.ReachedLess()) continue;
      std::string rooms;
      for (const auto& u : r.unreachable_rooms) {
        if (u.objects.empty()) continue;  // the floor outside a house's walls
        rooms += (rooms.empty() ? "" : "; ") + std::string("room ") + std::to_string(u.room) + " (" + Fix(u.area_m2, 1) +
                 " m2): ";
        for (std::size_t k = 0; k < u.objects.size(); ++k) rooms += (k ? ", " : "") + u.objects[k];
      }
      std::string left;
      for (std::size_t k = 0; k < r.objects_left.size(); ++k) left += (k ? ", " : "") + std::to_string(r.objects_left[k]);
      md << "| " << r.scene_id << " | `" << r.method << "` | " << r.terminated << " | " << (rooms.empty() ? "-" : rooms)
         << " | "
         << (r.has_reachable ? Pct(r.recall_reachable) + " / " + Pct(r.precision_reachable) + " (" +
                                   std::to_string(r.ground_truth_reachable) + " objects)"
                             : std::string("-"))
         << " | "
         << (r.unreachable_frontiers ? std::to_string(r.unreachable_frontiers) + " (" +
                                           Fix(r.unreachable_frontier_area_m2, 2) + " m2)"
                                     : std::string("-"))
         << " | " << (left.empty() ? "-" : left) << " | ";
      for (std::size_t k = 0; k < r.never_seen.size(); ++k) md << (k ? ", " : "") << r.never_seen[k];
      md << (r.never_seen.empty() ? "- |\n" : " |\n");
    }
  }
  md << "\n## Plots\n\n";
  for (const char* p : {"table1_recognition", "fig10a_rand_index", "fig10b_rand_index_views", "fig11a_coverage_rate_views",
                        "fig11b_coverage_quality_views", "fig12_frontier_coverage", "fig13a_coverage_travel",
                        "fig13b_quality_nbos", "fig14_database_parts", "table3_timing"}) {
    md << "- [" << p << "](" << p << ".svg) ([png](" << p << ".png))\n";
  }
  return md.str();
}

std::vector<std::string> WriteReport(const Report& report, const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw InputError(out_dir + ": cannot create the report folder: " + ec.message());
  io::RemoveStaleTempFiles(out_dir);  // left by a report writer that was killed
  const fs::path dir(out_dir);
  std::vector<std::string> written;
  io::WriteFileAtomically((dir / "results.json").string(), ReportJson(report));
  io::WriteFileAtomically((dir / "results.md").string(), ReportMarkdown(report));
  written = {"results.json", "results.md"};
  const std::string confusion = ConfusionCsv(report);
  if (!confusion.empty()) {
    io::WriteFileAtomically((dir / "confusion.csv").string(), confusion);
    written.push_back("confusion.csv");
  }
  auto save = [&](const auto& plot, const std::string& name) {
    SavePlot(plot, (dir / name).string());
    written.push_back(name + ".svg");
    written.push_back(name + ".png");
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> groups;
  for (const auto& c : report.scene_categories) groups.push_back(c);

  auto by_category = [&](const std::string& method, auto field) {
    std::vector<double> v;
    for (const auto& c : report.scene_categories) {
      const auto* s = Stats(report, method, c);
      v.push_back(s ? field(*s) : nan);
    }
    return v;
  };
  {
    BarPlot p;
    p.title = "Object recognition per scene category (Table 1)";
    p.y_label = "rate";
    p.groups = groups;
    p.y_min = 0.0;
    p.y_max = 1.0;
    std::vector<double> paper_recall, paper_precision;
    for (const auto& c : report.scene_categories) {
      const PaperSceneRow* row = PaperScene(c);
      paper_recall.push_back(row ? row->recall_pct / 100 : nan);
      paper_precision.push_back(row ? row->precision_pct / 100 : nan);
    }
    p.series = {{"recall (ours)", by_category("ours", [](const auto& s) { return s.recall; }), PlotColor(0)},
                {"precision (ours)", by_category("ours", [](const auto& s) { return s.precision; }), PlotColor(1)},
                {"recall (paper)", paper_recall, {158, 202, 225}},
                {"precision (paper)", paper_precision, {253, 208, 162}}};
    save(p, "table1_recognition");
  }
  {
    BarPlot p;
    p.title = "Rand Index per scene category (Fig. 10a)";
    p.y_label = "Rand Index";
    p.groups = groups;
    p.y_min = 0.0;
    p.y_max = 1.0;
    p.series = {{"ours", by_category("ours", [](const auto& s) { return s.rand_index; }), PlotColor(0)},
                {"preseg-only", by_category("preseg-only", [](const auto& s) { return s.rand_index; }), PlotColor(1)},
                {"pre-segmentation (ours)", by_category("ours", [](const auto& s) { return s.rand_index_preseg; }),
                 PlotColor(6)}};
    save(p, "fig10a_rand_index");
  }
  {
    LinePlot p;
    p.title = "Rand Index against views (Fig. 10b)";
    p.x_label = "views";
    p.y_label = "Rand Index";
    p.y_min = 0.0;
    p.y_max = 1.0;
    int color = 0;
    for (const char* m : {"ours", "preseg-only"}) {
      const std::vector<const RunSummary*> runs = Select(report, m, "all", true);
      // Mean over runs of the latest Rand Index at or before each view count.
      int max_views = 0;
      for (const RunSummary* r : runs) {
        for (const auto& [v, ri] : r->rand_index_per_view) max_views = std::max(max_views, v);
      }
      PlotSeries curve;
      curve.label = m;
      curve.color = PlotColor(color);
      for (int v = 1; v <= max_views; ++v) {
        double sum = 0.0;
        int n = 0;
        for (const RunSummary* r : runs) {
          const std::pair<int, double>* latest = nullptr;
          for (const auto& e : r->rand_index_per_view) {
            if (e.first <= v) latest = &e;
          }
          if (latest) sum += latest->second, ++n;
        }
        if (n > 0) {
          curve.x.push_back(v);
          curve.y.push_back(sum / n);
        }
      }
      PlotSeries dots;
      dots.label = std::string(m) + " (final, no per-view data)";
      dots.line = false;
      dots.markers = true;
      dots.color = PlotColor(color);
      for (const RunSummary* r : runs) {
        if (!r->rand_index_per_view.empty()) continue;
        dots.x.push_back(r->views);
        dots.y.push_back(r->rand_index);
      }
      if (!curve.x.empty()) p.series.push_back(curve);
      if (!dots.x.empty()) p.series.push_back(dots);
      ++color;
    }
    save(p, "fig10b_rand_index_views");
  }
  for (int quality = 0; quality < 2; ++quality) {
    LinePlot p;
    p.title = quality ? "Coverage quality over views (Fig. 11)" : "Coverage rate over views (Fig. 11)";
    p.x_label = "number of views";
    p.y_label = quality ? "coverage quality" : "coverage rate";
    p.y_min = 0.0;
    p.highlight_label = "switch to next object (NBO)";
    p.note = "ours; one scene per category (the first by id)";
    int color = 0;
    for (const auto& c : report.scene_categories) {
      const RunSummary* r = ExampleRun(report, c);
      if (!r) continue;
      PlotSeries s;
      s.label = c;
      s.color = PlotColor(color++);
      for (const auto& v : r->coverage) {
        s.x.push_back(v.view);
        s.y.push_back(quality ? v.quality : v.rate);
        if (v.nbo_switch) {
          s.highlight_x.push_back(v.view);
          s.highlight_y.push_back(quality ? v.quality : v.rate);
        }
      }
      p.series.push_back(s);
    }
    save(p, quality ? "fig11b_coverage_quality_views" : "fig11a_coverage_rate_views");
  }
  {
    BarPlot p;
    p.title = "Object coverage: object guidance vs frontier exploration";
    p.y_label = "coverage";
    p.groups = groups;
    p.y_min = 0.0;
    p.series = {{"rate (ours)", by_category("ours", [](const auto& s) { return s.coverage_rate; }), PlotColor(0)},
                {"rate (frontier)", by_category("frontier", [](const auto& s) { return s.coverage_rate; }), {158, 202, 225}},
                {"quality (ours)", by_category("ours", [](const auto& s) { return s.coverage_quality; }), PlotColor(1)},
                {"quality (frontier)", by_category("frontier", [](const auto& s) { return s.coverage_quality; }),
                 {253, 208, 162}}};
    save(p, "fig12_frontier_coverage");
  }
  {
    LinePlot p, q;
    p.title = "Coverage rate over travel distance (Fig. 13)";
    p.x_label = "robot travel (m)";
    p.y_label = "coverage rate (mean over scenes)";
    p.y_min = 0.0;
    q.title = "Coverage quality over NBOs (Fig. 13)";
    q.x_label = "number of objects visited (NBO)";
    q.y_label = "coverage quality (mean over scenes)";
    q.y_min = 0.0;
    int color = 0;
    for (const auto& m : AblationMethods()) {
      const auto runs = Select(report, m, "all", true);
      if (runs.empty()) {
        ++color;
        continue;
      }
      const Curve c = MeanCoverageOverTravel(runs, 41, false);
      const Curve d = MeanQualityOverNbos(runs);
      p.series.push_back(PlotSeries::Line(m, c.x, c.y, PlotColor(color)));
      q.series.push_back(PlotSeries::Line(m, d.x, d.y, PlotColor(color)));
      ++color;
    }
    save(p, "fig13a_coverage_travel");
    save(q, "fig13b_quality_nbos");
  }
  {
    BarPlot p;
    p.title = "Database with / without part entries (Fig. 14)";
    p.y_label = "rate";
    p.groups = groups;
    p.y_min = 0.0;
    p.y_max = 1.0;
    p.series = {{"recall (ours)", by_category("ours", [](const auto& s) { return s.recall; }), PlotColor(0)},
                {"recall (db-no-parts)", by_category("db-no-parts", [](const auto& s) { return s.recall; }),
                 {158, 202, 225}},
                {"precision (ours)", by_category("ours", [](const auto& s) { return s.precision; }), PlotColor(1)},
                {"precision (db-no-parts)", by_category("db-no-parts", [](const auto& s) { return s.precision; }),
                 {253, 208, 162}}};
    save(p, "fig14_database_parts");
  }
  {
    BarPlot p;
    p.title = "Running time per scene category (Table 3, ours)";
    p.y_label = "seconds per scene";
    p.groups = groups;
    p.y_min = 0.0;
    p.note = "navigate = simulated driving time; the others are compute wall time";
    p.series = {
        {"navigate (sim)", by_category("ours", [](const auto& s) { return s.timing_s.navigate_sim; }), PlotColor(0)},
        {"segment", by_category("ours", [](const auto& s) { return s.timing_s.segment; }), PlotColor(1)},
        {"recognize", by_category("ours", [](const auto& s) { return s.timing_s.recognize; }), PlotColor(2)},
        {"NBO", by_category("ours", [](const auto& s) { return s.timing_s.nbo; }), PlotColor(3)},
        {"NBV", by_category("ours", [](const auto& s) { return s.timing_s.nbv; }), PlotColor(4)}};
    save(p, "table3_timing");
  }
  return written;
}

}  // namespace objscan::eval
