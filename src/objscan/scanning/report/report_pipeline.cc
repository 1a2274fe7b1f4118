#include "objscan/scanning/report/report_pipeline.h"

#include <set>

#include "objscan/common/error.h"
#include "objscan/scanning/report/report_rules.h"

namespace objscan::scanning {

std::vector<std::string> DefaultReportRules() {
  // drop_unsure left the list when the Sweet Home 3D library became the database of real scenes: with
  // it the rule no longer bought precision on OASC dev (36.0 -> 35.9 without it) and cost recall
  // there (43.5 -> 49.3) and on procedural rooms (seeds 1-3: 70.6 / 87.0 -> 82.1 / 83.2);
  // docs/results/oasc-dev-2026-11-28-category-recognizer.md.
  // name_by_shape (scope "unfinished") joined it when the category recognizer learned from the
  // procedural database's shapes too: OASC dev 49.3 / 35.9 / 43.0 -> 53.0 / 38.6 / 44.4, procedural
  // seeds 4-6 79.9 / 82.5 / 79.0 -> 80.4 / 82.0 / 78.1 (docs/results/recognizer-training-shapes-2026-11-28.md).
  return {"model_label",   "name_by_shape", "absorb_fragments",  "regroup_by_size", "join_stacked",
          "door_depth",    "wall_openings", "size_check",        "curtain_must_hang", "relabel",
          "join_window_pieces", "curtains_over_windows", "drop_small"};
}

std::vector<std::string> AllReportRules() {
  // reopen_outgrown runs first when listed (it reopens objects the later rules then treat as
  // unfinished); off by default: it cost recall and coverage on the OASC dev worlds.
  std::vector<std::string> all = {"reopen_outgrown"};
  for (const std::string& name : DefaultReportRules()) all.push_back(name);
  all.push_back("drop_unsure");
  all.push_back("shape_agrees");
  return all;
}

std::unique_ptr<ReportRule> MakeReportRule(const std::string& name, const ReportOptions& options) {
  if (name == "reopen_outgrown") return std::make_unique<ReopenOutgrownRule>(options.completion_check, options.wall_openings);
  if (name == "model_label") return std::make_unique<ModelLabelRule>(options.model_label_min_objectness);
  if (name == "absorb_fragments") return std::make_unique<AbsorbFragmentsRule>(options.fragments);
  if (name == "regroup_by_size") return std::make_unique<RegroupBySizeRule>(options.size_check);
  if (name == "join_stacked") return std::make_unique<JoinStackedRule>(options.size_check);
  if (name == "door_depth") return std::make_unique<DoorDepthRule>(options.wall_openings);
  if (name == "wall_openings") return std::make_unique<WallOpeningsRule>(options.wall_openings);
  if (name == "size_check") return std::make_unique<SizeCheckRule>(options.size_check);
  if (name == "curtain_must_hang") return std::make_unique<CurtainMustHangRule>(options.wall_openings);
  if (name == "relabel") return std::make_unique<RelabelRule>(options.size_check);
  if (name == "join_window_pieces") return std::make_unique<JoinWindowPiecesRule>(options.wall_openings);
  if (name == "curtains_over_windows") return std::make_unique<CurtainsOverWindowsRule>(options.wall_openings);
  if (name == "drop_small") return std::make_unique<DropSmallRule>(options.min_reported_elements);
  if (name == "drop_unsure") return std::make_unique<DropUnsureRule>(options.min_labelled_objectness);
  if (name == "shape_agrees") return std::make_unique<ShapeAgreesRule>(options.shape_min_odds);
  if (name == "name_by_shape") return std::make_unique<NameByShapeRule>(options.name_scope, options.name_adopts_model);
  return nullptr;
}

void ReportOptions::Validate() const {
  std::set<std::string> seen;
  for (const std::string& r : rules) {
    if (MakeReportRule(r, *this) == nullptr) {
      std::string known;
      for (const std::string& k : AllReportRules()) known += (known.empty() ? "" : ", ") + k;
      throw ConfigError("config: report.rules: unknown rule '" + r + "' (known: " + known + ")");
    }
    config::Require(seen.insert(r).second, "report.rules", "lists '" + r + "' twice");
  }
  completion_check.Validate();
  config::RequireInRange("report.model_label_min_objectness", model_label_min_objectness, 0.0, 1.0);
  fragments.Validate();
  size_check.Validate();
  wall_openings.Validate();
  config::Require(min_reported_elements >= 0, "report.min_reported_elements", "must be >= 0");
  config::RequireInRange("report.min_labelled_objectness", min_labelled_objectness, 0.0, 1.0);
  config::RequireInRange("report.shape_min_odds", shape_min_odds, 0.0, 1.0);
  config::Require(name_scope == "all" || name_scope == "unfinished" || name_scope == "other", "report.name_scope",
                  "must be 'all', 'unfinished' or 'other', not '" + name_scope + "'");
}

ReportPipeline::ReportPipeline(const ReportOptions& options) {
  options.Validate();
  for (const std::string& r : options.rules) rules_.push_back(MakeReportRule(r, options));
}

bool ReportPipeline::needs_category_extents() const {
  for (const auto& r : rules_) {
    if (r->needs_category_extents()) return true;
  }
  return false;
}

std::vector<std::string> ReportPipeline::rule_names() const {
  std::vector<std::string> names;
  for (const auto& r : rules_) names.push_back(r->name());
  return names;
}

void ReportPipeline::Run(const ReportContext& context, ReportedObjects* objects) const {
  for (const auto& r : rules_) r->Apply(context, objects);
}

}  // namespace objscan::scanning
