// Report rules about an object's size: regroup_by_size, join_stacked, size_check, relabel.
#include <algorithm>

#include "objscan/scanning/report/label_replacement.h"
#include "objscan/scanning/report/report_rules.h"
#include "objscan/scanning/report/size_regrouping.h"

namespace objscan::scanning {
namespace {

// The reported objects as regrouping candidates (copies of their points; completed ones are fixed and
// unlabelled there); objects no longer reported are empty and unlabelled, so they touch nothing.
std::vector<RegroupCandidate> RegroupCandidates(const ReportedObjects& objects) {
  std::vector<RegroupCandidate> pieces(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const ReportedObject& o = objects[i];
    if (!o.reported()) continue;
    pieces[i].points_world = o.points_world;
    pieces[i].category = o.record.complete ? std::nullopt : o.record.category;
    pieces[i].fixed = o.record.complete;
  }
  return pieces;
}

// The object that i's host `into` is reported in now (hosts may have joined others before i).
std::size_t ReportedHost(const ReportedObjects& objects, std::size_t into) {
  while (!objects[into].reported()) into = static_cast<std::size_t>(objects[into].joined_into);
  return into;
}

// Hands the regrouped points back and joins each piece to its host.
void ApplyRegrouping(RegroupResult result, bool relabel_hosts, const char* rule, ReportedObjects* objects) {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    if ((*objects)[i].reported()) objects->mutable_object(i).points_world = std::move(result.points_world[i]);
  }
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported()) continue;
    const std::size_t into = static_cast<std::size_t>(result.host[i]);
    if (into == i) {
      if (relabel_hosts && !o.record.complete) objects->Relabel(i, result.category[i], rule);
      continue;
    }
    objects->Join(i, ReportedHost(*objects, into), rule);
  }
}

}  // namespace

recognition::ObjectExtent MeasureReportedExtent(const ReportContext& context, const ReportedObjects& objects,
                                                std::size_t i, const recognition::SizePlausibilityOptions& options) {
  return recognition::MeasureObjectExtent(
      PointsAwayFromWalls(objects[i].points_world, *context.structure, options.wall_margin_m), options);
}

void RegroupBySizeRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  std::vector<std::vector<Eigen::Vector3f>> points(objects->size());
  for (std::size_t i = 0; i < objects->size(); ++i) {
    if ((*objects)[i].reported()) points[i] = (*objects)[i].points_world;
  }
  std::vector<std::pair<int, int>> adjacency = ObjectsWithinDistance(points, options_.adjacency_m);
  const auto stacked = ObjectsStandingUnder(points, options_.support_gap_m, options_.adjacency_m);
  adjacency.insert(adjacency.end(), stacked.begin(), stacked.end());
  std::sort(adjacency.begin(), adjacency.end());
  adjacency.erase(std::unique(adjacency.begin(), adjacency.end()), adjacency.end());
  // The categories a union of objects is recognized as, best first.
  const auto recognize = [&](const std::vector<int>& members) {
    std::vector<std::int32_t> labels;
    for (int m : members) {
      const auto& l = (*objects)[static_cast<std::size_t>(m)].record.labels;
      labels.insert(labels.end(), l.begin(), l.end());
    }
    std::sort(labels.begin(), labels.end());
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    std::vector<world::Category> categories;
    for (const auto& m : context.sources->MatchFullModels(labels).models) categories.push_back(m.category);
    return categories;
  };
  ApplyRegrouping(RegroupImplausibleFragments(RegroupCandidates(*objects), adjacency, *context.category_extents,
                                              options_, recognize),
                  true, name(), objects);
}

void JoinStackedRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  ApplyRegrouping(JoinStackedPieces(RegroupCandidates(*objects), options_.support_gap_m, options_.adjacency_m,
                                    *context.category_extents, options_),
                  false, name(), objects);
}

void SizeCheckRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || o.record.complete || !o.record.category) continue;
    // A window in a wall opening keeps its label: the opening bounds it, and what the object holds
    // beyond it are strips of the wall around the opening.
    if (o.in_wall_opening && o.record.category == world::Category::kWindow) continue;
    const recognition::ObjectExtent extent = MeasureReportedExtent(context, *objects, i, options_);
    if (recognition::IsPlausibleExtent(extent, context.category_extents->Find(*o.record.category), options_)) continue;
    objects->TakeLabel(i, name());
  }
}

void RelabelRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || !o.taken || o.full_matches == nullptr) continue;
    const recognition::ObjectExtent extent = MeasureReportedExtent(context, *objects, i, options_);
    const segmentation::ModelMatch* replacement = ReplacementLabel(
        *o.taken, *o.full_matches, extent, o.in_wall_opening, *context.category_extents, options_);
    if (replacement != nullptr) {
      objects->Adopt(i, *replacement, context.sources->ModelName(replacement->model_id), name());
    }
  }
}

}  // namespace objscan::scanning
