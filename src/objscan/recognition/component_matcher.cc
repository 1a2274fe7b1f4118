#include "objscan/recognition/component_matcher.h"

#include <algorithm>
#include <stdexcept>

#include "objscan/sim/parallel_for.h"

namespace objscan::recognition {

segmentation::MatchResult RecognizerComponentMatcher::Match(const std::vector<std::int32_t>& component_ids,
                                                             segmentation::MatchScope scope) {
  if (!graph_) throw std::logic_error("RecognizerComponentMatcher: SetComponents was not called");
  geometry::PointCloud union_cloud;
  for (std::int32_t id : component_ids) {
    const segmentation::Component* c = graph_->Find(id);
    if (!c) continue;
    union_cloud.points.insert(union_cloud.points.end(), c->points.begin(), c->points.end());
    union_cloud.normals.insert(union_cloud.normals.end(), c->normals.begin(), c->normals.end());
  }
  segmentation::MatchResult result;
  if (union_cloud.empty()) return result;
  const RetrievalScope s =
      scope == segmentation::MatchScope::kFullModels ? RetrievalScope::kFullModels : RetrievalScope::kAllEntries;
  const ModelDatabase& db = recognizer_.database();
  for (const SimilarModel& m : recognizer_.Retrieve(recognizer_.Describe(union_cloud), s)) {
    const DatabaseEntry& e = db.entries()[m.entry];
    segmentation::ModelMatch match;
    match.entry_id = m.entry;
    match.model_id = e.model_index;
    match.category = e.category;
    match.full_model = e.kind == EntryKind::kFullModel;
    match.objectness = m.objectness.objectness;
    // Rigid part of the alignment (a uniform scale, when estimated, is left out of the pose).
    const Eigen::Affine3d T = m.T_world_model();
    geometry::Pose3 pose = geometry::Pose3::Identity();
    pose.linear() = T.linear() / std::cbrt(std::abs(T.linear().determinant()));
    pose.translation() = T.translation();
    match.T_world_model = pose;
    result.models.push_back(match);
  }
  // The interface orders M(X) by objectness, best first.
  std::stable_sort(result.models.begin(), result.models.end(),
                   [](const segmentation::ModelMatch& a, const segmentation::ModelMatch& b) {
                     return a.objectness > b.objectness;
                   });
  return result;
}

std::vector<segmentation::MatchResult> RecognizerComponentMatcher::MatchBatch(
    const std::vector<std::vector<std::int32_t>>& queries, segmentation::MatchScope scope) {
  std::vector<segmentation::MatchResult> results(queries.size());
  sim::ParallelForBlocks(static_cast<int>(queries.size()), threads_,
                         [&](int i) { results[i] = Match(queries[i], scope); });
  return results;
}

}  // namespace objscan::recognition
