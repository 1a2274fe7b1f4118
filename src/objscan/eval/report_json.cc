// The report as data: results.json, reported_objects.json and confusion.csv.
#include "objscan/eval/report.h"

#include <nlohmann/json.hpp>
#include <sstream>

#include "objscan/eval/report_internal.h"
#include "objscan/world/category.h"

namespace objscan::eval {
using Json = nlohmann::ordered_json;
using namespace report_internal;  // NOLINT: the report files share these helpers

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

}  // namespace objscan::eval
