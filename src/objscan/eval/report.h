#pragma once
// The report of `objscan bench` / `objscan report`: reads the run.json of finished runs (from one
// bench folder or several shards), aggregates them like the paper's Results section (Tables 1-3,
// Figs. 10, 11, 13, 14) with the paper's published figures beside ours, and writes results.md,
// results.json and SVG + PNG plots. results.json depends only on the runs found (sorted by scene and
// method), so shards merged give the same file as one bench over the whole suite. With ground truth
// it also says where the reported objects go wrong (error_analysis.h): confusion.csv, and the error
// classes of every reported labelled object per method.
#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "objscan/eval/error_analysis.h"

namespace objscan::eval {

// One view of a run's coverage curve.
struct CoveragePoint {
  int view = 0;           // 1-based
  double travel_m = 0.0;  // robot travel when the view was taken
  double rate = 0.0, quality = 0.0;
  bool nbo_switch = false;  // first view after the robot switched to a next best object
};

struct RunTiming {
  double total = 0, sense = 0, fuse = 0, segment = 0, recognize = 0, nbo = 0, nbv = 0, navigate_sim = 0;
};

struct CategoryCounts {
  int ground_truth = 0, outputs = 0, true_positives = 0;
};

// What became of one ground-truth instance of a run (metrics.instances): the coverage breakdown.
struct ReportedInstance {
  std::string category;
  int surface_voxels = 0;  // its voxels in V_S
  int visible_voxels = 0;  // of those, seen within range
  bool matched = false;    // a true positive: its surface counts towards coverage_rate
  // The label of the output object holding most of its points ("unlabelled" for an object without
  // one, "not reported" when no object holds its points).
  std::string reported_as;
};

// One run (a run.json, or a failed.json without a run.json).
struct RunSummary {
  std::string scene_id, method, scene_spec, scene_category;
  bool failed = false;
  int exit_code = 0;
  std::string terminated;
  bool has_metrics = false;
  double recall = 0, precision = 0, recall_floor = 0, precision_floor = 0;
  int ground_truth_objects = 0, ground_truth_floor_objects = 0, output_objects = 0, true_positives = 0;
  double rand_index = 0, rand_index_preseg = 0, preseg_purity = 0;
  double coverage_rate = 0, coverage_quality = 0, travel_m = 0;
  int views = 0, nbo_count = 0, steps = 0;
  double nbv_per_object = 0;
  std::map<std::string, CategoryCounts> per_category;
  std::vector<ReportedInstance> instances;
  std::vector<CoveragePoint> coverage;
  std::vector<std::pair<int, double>> rand_index_per_view;  // (views seen, Rand Index) per analysis
  RunTiming timing_s;
  // Resources of the run's process (run.json peak_rss_mb, cpu_s); negative when run.json lacks them
  // (written before objscan recorded them).
  double peak_rss_mb = -1.0, cpu_s = -1.0;
  // The reported labelled objects (the outputs of recall and precision: labelled, and complete or
  // with objectness >= the run's eval.recognized_min_objectness) by error class, and the confusion
  // matrix; when run.json lists the ground-truth instances (metrics.instances).
  bool has_error_analysis = false;
  ErrorBreakdown errors;
  ConfusionMatrix confusion;
  // What the run could not reach (absent from run.json files written before these were recorded):
  // the robot's own account (unreachable frontiers, objects left for want of a reachable view) and
  // the ground truth's (rooms behind closed doors, with recall and precision over the other rooms).
  int unreachable_frontiers = 0;
  double unreachable_frontier_area_m2 = 0.0;
  std::vector<int> objects_left;
  struct UnreachableRoomSummary {
    int room = 0;
    double area_m2 = 0.0;
    std::vector<std::string> objects;  // "name (category)"
  };
  std::vector<UnreachableRoomSummary> unreachable_rooms;
  std::vector<std::string> never_seen;  // metrics.never_seen: "name (category)"
  bool has_reachable = false;
  int ground_truth_reachable = 0;
  double recall_reachable = 0, precision_reachable = 0;
  // Something was out of reach: frontiers, objects left, or a room holding objects (a room without
  // any, such as the floor outside a house's walls, does not count).
  bool ReachedLess() const {
    return unreachable_frontiers > 0 || !objects_left.empty() ||
           std::any_of(unreachable_rooms.begin(), unreachable_rooms.end(),
                       [](const UnreachableRoomSummary& u) { return !u.objects.empty(); });
  }
};

// Parses run.json text. `scene_id` and `method` name the run (from its folder). Throws InputError
// naming `source` when the text is not a run.json.
RunSummary ParseRunJson(const std::string& text, const std::string& scene_id, const std::string& method,
                        const std::string& source);

// The folders of `dirs` below which there is no run.json or failed.json (a typo, an empty or
// unfinished folder); `objscan report` refuses them. Throws InputError for a folder that does not exist.
std::vector<std::string> FoldersWithoutRuns(const std::vector<std::string>& dirs);

// Every run under the folders (searched recursively; report/ folders skipped). A run folder
// .../runs/<scene-id>/<method>/ names its scene and method; any other run.json is method "ours" with
// the folder name as scene id. The same (scene, method) found twice counts once (a complete run wins
// over a failed one, then the first path in sorted order). Sorted by (scene id, method). Throws
// InputError naming a folder that does not exist or a run.json that cannot be read.
std::vector<RunSummary> CollectRuns(const std::vector<std::string>& dirs);

// Paper figures (Tables 1-3 of the paper, hard-coded).
struct PaperSceneRow {
  const char* category;
  int scenes, objects_per_scene;
  double recall_pct, precision_pct, recall_floor_pct, precision_floor_pct;
};
struct PaperObjectRow {
  const char* category;
  int objects;
  double recall_pct, precision_pct;
};
struct PaperTimingRow {
  const char* category;
  double total_min, navigate_min, segment_min, nbo_min, nbv_min;
};
const std::vector<PaperSceneRow>& PaperTable1();
const std::vector<PaperObjectRow>& PaperTable2();
const std::vector<PaperTimingRow>& PaperTable3();

// Aggregates over the complete runs of one method in one scene category (or all: "all").
struct SceneCategoryStats {
  std::string category;
  int scenes = 0;        // complete runs
  int failed = 0;
  double objects_per_scene = 0;  // mean ground-truth objects
  double recall = 0, precision = 0, recall_floor = 0, precision_floor = 0;  // means over scenes
  double rand_index = 0, rand_index_preseg = 0;
  double coverage_rate = 0, coverage_quality = 0, travel_m = 0, views = 0, nbo_count = 0;
  RunTiming timing_s;  // means
  // Process resources over the complete runs that recorded them (each counted separately: older
  // run.json files lack cpu_s). Means and maxima; 0 when no run recorded it.
  int cpu_runs = 0, rss_runs = 0;
  double cpu_s = 0, cpu_s_max = 0;
  double peak_rss_mb = 0, peak_rss_mb_max = 0;
};

struct ObjectCategoryStats {
  std::string category;
  CategoryCounts counts;  // summed over scenes
  double recall = 0, precision = 0;  // tp / ground truth, tp / outputs (0 when the divisor is 0)
};

// Where the coverage rate goes, per ground-truth object category (method "ours"), as shares of V_S
// averaged over runs like coverage_rate: summed over the categories, `covered` gives the mean
// coverage_rate and `seen` the mean share of V_S seen within range.
struct CoverageBreakdownRow {
  std::string category;
  double surface = 0;  // share of V_S
  double seen = 0;     // seen within range
  double covered = 0;  // seen, on a matched instance
  // The seen surface of unmatched instances by what they were reported as, largest first.
  std::vector<std::pair<std::string, double>> missed_as;
};

// Error classes and confusion matrix summed over the complete runs of a method that have them.
struct MethodErrors {
  std::string method;  // a method, or "all": every method together
  int runs = 0;
  ErrorBreakdown breakdown;
  ConfusionMatrix confusion;
};

// A mean curve over the runs of a group: y at each x (runs that ended earlier hold their last value).
struct Curve {
  std::string label;
  std::vector<double> x, y;
};

struct Report {
  std::vector<std::string> methods;           // in report order
  std::vector<std::string> scene_categories;  // present, in the paper's order
  std::map<std::string, std::vector<SceneCategoryStats>> by_method;  // per scene category, then "all"
  std::vector<ObjectCategoryStats> object_categories;  // method "ours"
  std::vector<CoverageBreakdownRow> coverage_breakdown;  // method "ours", largest surface first
  // Per method in report order, then "all"; empty when no run has an error analysis.
  std::vector<MethodErrors> errors;
  std::vector<RunSummary> runs;
  int complete_runs = 0, failed_runs = 0;
};

Report BuildReport(std::vector<RunSummary> runs);

// Mean curves: coverage rate against travel distance (Fig. 13), sampled at `samples` points from 0
// to the longest travel of the runs; coverage (rate or quality) against views.
Curve MeanCoverageOverTravel(const std::vector<const RunSummary*>& runs, int samples, bool quality);
Curve MeanCoverageOverViews(const std::vector<const RunSummary*>& runs, bool quality);
// Coverage quality after each completed object (x = number of NBOs so far).
Curve MeanQualityOverNbos(const std::vector<const RunSummary*>& runs);

std::string ReportJson(const Report& report);
std::string ReportMarkdown(const Report& report);
// JSON text of the error classes per method and overall, counts and shares (results.json's
// "reported_objects"; the commands print it too).
std::string ReportedObjectsJson(const Report& report);
// CSV text of the confusion matrices: columns method, ground_truth, one per reported category of
// any method, missed, total; one line per (method, ground-truth row), "all" lines only when the
// report has several methods. Empty when no run has an error analysis.
std::string ConfusionCsv(const Report& report);
// Writes results.md, results.json, confusion.csv (when some run has an error analysis) and the
// plots (SVG + PNG) into `out_dir` (created when missing). Returns the files written (relative to
// out_dir).
std::vector<std::string> WriteReport(const Report& report, const std::string& out_dir);

}  // namespace objscan::eval
