// The report folder: every table, figure and data file WriteReport writes.
#include "objscan/eval/report.h"

#include <filesystem>

#include "objscan/common/error.h"
#include "objscan/eval/plot.h"
#include "objscan/eval/report_internal.h"
#include "objscan/io/atomic_file.h"
#include "objscan/world/category.h"

namespace objscan::eval {
namespace fs = std::filesystem;
using namespace report_internal;  // NOLINT: the report files share these helpers

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
