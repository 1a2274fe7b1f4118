// The report as a page: results.md, the paper's tables beside ours.
#include "objscan/eval/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "objscan/eval/report_internal.h"
#include "objscan/world/category.h"

namespace objscan::eval {
using namespace report_internal;  // NOLINT: the report files share these helpers

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

}  // namespace objscan::eval
