// Report rules about an object's model and how sure recognition is: reopen_outgrown, model_label,
// absorb_fragments, drop_small, drop_unsure.
#include "objscan/scanning/report/completion_check.h"
#include "objscan/scanning/report/fragment_absorption.h"
#include "objscan/scanning/report/label_replacement.h"
#include "objscan/scanning/report/report_rules.h"
#include "objscan/scanning/report/wall_openings.h"

namespace objscan::scanning {

void ReopenOutgrownRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || !o.record.complete) continue;
    const std::vector<Eigen::Vector3f> model_points = context.sources->EntryPoints(o.model_entry);
    // A door model fits any flat face; what was seen of a door leaf lies in a thin slab.
    const bool check_door = o.record.category == world::Category::kDoor;
    if (model_points.empty() && !check_door) continue;
    std::vector<Eigen::Vector3f> seen = context.sources->ComponentPoints(o.record.labels);
    bool reopen = check_door && TooDeepForADoor(seen, doors_);
    if (!reopen && !model_points.empty()) {
      reopen = ShareOutsideModelBox(seen, model_points, o.record.T_world_model, options_.margin_m) >
               options_.max_outside_share;
    }
    if (!reopen) continue;
    segmentation::MatchResult matches = context.sources->MatchFullModels(o.record.labels);
    const std::string best_name =
        matches.models.empty() ? std::string() : context.sources->ModelName(matches.models.front().model_id);
    objects->Reopen(i, std::move(matches), std::move(seen), best_name, name());
  }
}

void ModelLabelRule::Apply(const ReportContext& /*context*/, ReportedObjects* objects) const {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || o.record.complete || o.full_matches == nullptr || o.full_matches->models.empty()) continue;
    objects->Relabel(i, ModelLabel(o.record.category, &o.full_matches->models.front(), min_objectness_), name());
  }
}

void NameByShapeRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || !o.record.category) continue;
    if (scope_ == "unfinished" && o.record.complete) continue;
    if (scope_ == "other" && o.record.category != world::Category::kOther) continue;
    std::vector<recognition::RetrievedCategory> votes;
    if (o.full_matches != nullptr) {
      for (const segmentation::ModelMatch& m : o.full_matches->models) votes.push_back({m.category, m.objectness});
    } else {
      votes.push_back({*o.record.category, o.record.objectness});
    }
    const std::optional<world::Category> named = context.sources->NameCategory(o.record.labels, votes);
    if (!named || named == o.record.category) continue;
    const std::optional<segmentation::ModelMatch> best =
        adopt_model_ ? context.sources->BestOfCategory(o.record.labels, *named) : std::nullopt;
    if (best) {
      objects->Adopt(i, *best, context.sources->ModelName(best->model_id), name());
    } else {
      objects->Relabel(i, *named, name());
    }
  }
}

void AbsorbFragmentsRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  std::vector<FragmentCandidate> candidates(objects->size());
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    FragmentCandidate& f = candidates[i];
    if (!o.reported()) {
      f.may_be_absorbed = false;
      continue;
    }
    f.points_world = o.points_world;
    f.num_points = o.num_elements;
    f.objectness = o.record.objectness;
    f.model_points = context.sources->EntryPoints(o.model_entry);
    f.T_world_model = o.record.T_world_model;
    f.may_be_absorbed = !o.record.complete;  // a completed object is its model
  }
  const std::vector<int> host = AbsorbExplainedFragments(candidates, options_);
  for (std::size_t i = 0; i < host.size(); ++i) {
    if (host[i] != static_cast<int>(i)) objects->Join(i, static_cast<std::size_t>(host[i]), name());
  }
}

void DropSmallRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || !o.record.category) continue;
    if (context.sources->ElementCount(o.record.labels) >= static_cast<std::size_t>(std::max(0, min_elements_))) {
      continue;
    }
    objects->TakeLabel(i, name());
  }
}

void DropUnsureRule::Apply(const ReportContext& /*context*/, ReportedObjects* objects) const {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || !o.record.category || o.record.complete || o.record.objectness >= min_objectness_) continue;
    objects->TakeLabel(i, name());
  }
}

void ShapeAgreesRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || !o.record.category) continue;
    const std::vector<float> odds = context.sources->CategoryOdds(o.record.labels);
    const auto k = static_cast<std::size_t>(world::CategoryId(*o.record.category));
    if (k >= odds.size() || static_cast<double>(odds[k]) >= min_odds_) continue;
    objects->TakeLabel(i, name());
  }
}

}  // namespace objscan::scanning
