#include "objscan/recognition/component_matcher.h"

#include <algorithm>
#include <stdexcept>

#include "objscan/common/parallel_for.h"

namespace objscan::recognition {

namespace {

geometry::PointCloud CloudOf(const segmentation::Component& c) {
  geometry::PointCloud cloud;
  cloud.points = c.points;
  cloud.normals = c.normals;
  return cloud;
}

segmentation::ModelMatch ToModelMatch(const ModelDatabase& db, const SimilarModel& m) {
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
  return match;
}

}  // namespace

void RecognizerComponentMatcher::SetComponents(const segmentation::ComponentGraph* graph) {
  graph_ = graph;
  for (auto it = descriptions_.begin(); it != descriptions_.end();) {
    const segmentation::Component* c = graph_ ? graph_->Find(it->first) : nullptr;
    it = (c == nullptr || c->revision != it->second.revision) ? descriptions_.erase(it) : std::next(it);
  }
}

void RecognizerComponentMatcher::DescribeMissing(const std::vector<std::vector<std::int32_t>>& queries) {
  if (!graph_) throw std::logic_error("RecognizerComponentMatcher: SetComponents was not called");
  std::vector<const segmentation::Component*> missing;
  for (const auto& ids : queries) {
    for (std::int32_t id : ids) {
      const segmentation::Component* c = graph_->Find(id);
      if (c == nullptr || c->points.empty()) continue;
      auto it = descriptions_.find(id);
      if (it != descriptions_.end() && it->second.revision == c->revision) continue;
      descriptions_[id] = CachedDescription{c->revision, nullptr};  // claimed; filled below
      missing.push_back(c);
    }
  }
  std::vector<QueryDescription> described(missing.size());
  ParallelForBlocks(static_cast<int>(missing.size()), threads_,
                         [&](int i) { described[i] = recognizer_.Describe(CloudOf(*missing[i])); });
  for (std::size_t i = 0; i < missing.size(); ++i) {
    descriptions_[missing[i]->label].description = std::make_shared<const QueryDescription>(std::move(described[i]));
  }
}

segmentation::MatchResult RecognizerComponentMatcher::Match(const std::vector<std::int32_t>& component_ids,
                                                             segmentation::MatchScope scope) {
  if (!graph_) throw std::logic_error("RecognizerComponentMatcher: SetComponents was not called");
  if (recognizer_.options().compose_unions) DescribeMissing({component_ids});
  return MatchDescribed(component_ids, scope);
}

const QueryDescription* RecognizerComponentMatcher::DescribedQuery(const std::vector<std::int32_t>& component_ids,
                                                                  QueryDescription* storage) const {
  if (recognizer_.options().compose_unions) {
    std::vector<const QueryDescription*> parts;
    for (std::int32_t id : component_ids) {
      auto it = descriptions_.find(id);
      if (it != descriptions_.end() && it->second.description) parts.push_back(it->second.description.get());
    }
    if (parts.empty()) return nullptr;
    if (parts.size() == 1) return parts.front();
    *storage = recognizer_.Compose(parts);
    return storage;
  }
  geometry::PointCloud union_cloud;
  for (std::int32_t id : component_ids) {
    const segmentation::Component* c = graph_->Find(id);
    if (!c) continue;
    union_cloud.points.insert(union_cloud.points.end(), c->points.begin(), c->points.end());
    union_cloud.normals.insert(union_cloud.normals.end(), c->normals.begin(), c->normals.end());
  }
  if (union_cloud.empty()) return nullptr;
  *storage = recognizer_.Describe(union_cloud);
  return storage;
}

segmentation::MatchResult RecognizerComponentMatcher::MatchDescribed(const std::vector<std::int32_t>& component_ids,
                                                                     segmentation::MatchScope scope) const {
  segmentation::MatchResult result;
  QueryDescription storage;
  const QueryDescription* query = DescribedQuery(component_ids, &storage);
  if (query == nullptr) return result;
  const RetrievalScope s =
      scope == segmentation::MatchScope::kFullModels ? RetrievalScope::kFullModels : RetrievalScope::kAllEntries;
  for (const SimilarModel& m : recognizer_.Retrieve(*query, s, space_)) {
    result.models.push_back(ToModelMatch(recognizer_.database(), m));
  }
  // The interface orders M(X) by objectness, best first.
  std::stable_sort(result.models.begin(), result.models.end(),
                   [](const segmentation::ModelMatch& a, const segmentation::ModelMatch& b) {
                     return a.objectness > b.objectness;
                   });
  return result;
}

std::optional<segmentation::ModelMatch> RecognizerComponentMatcher::BestOfCategory(
    const std::vector<std::int32_t>& component_ids, world::Category category) {
  if (!graph_) throw std::logic_error("RecognizerComponentMatcher: SetComponents was not called");
  if (recognizer_.options().compose_unions) DescribeMissing({component_ids});
  QueryDescription storage;
  const QueryDescription* query = DescribedQuery(component_ids, &storage);
  if (query == nullptr || query->empty()) return std::nullopt;
  const ModelDatabase& db = recognizer_.database();
  std::optional<segmentation::ModelMatch> best;
  for (const DatabaseModel& model : db.models()) {
    if (model.category != category || model.full_entry < 0) continue;
    const SimilarModel m = recognizer_.Match(*query, model.full_entry, space_);
    if (!m.alignment.ok()) continue;
    segmentation::ModelMatch match = ToModelMatch(db, m);
    if (!best || match.objectness > best->objectness) best = match;
  }
  return best;
}

std::vector<float> RecognizerComponentMatcher::CategoryOdds(const std::vector<std::int32_t>& component_ids) {
  if (!graph_) throw std::logic_error("RecognizerComponentMatcher: SetComponents was not called");
  if (recognizer_.options().compose_unions) DescribeMissing({component_ids});
  QueryDescription storage;
  const QueryDescription* query = DescribedQuery(component_ids, &storage);
  if (query == nullptr) return {};
  const std::optional<double> floor = space_ != nullptr ? space_->FloorHeight() : std::nullopt;
  return recognizer_.CategoryOdds(*query, floor.value_or(0.0));
}

std::optional<world::Category> RecognizerComponentMatcher::NameCategory(const std::vector<std::int32_t>& component_ids,
                                                                       const std::vector<RetrievedCategory>& votes) {
  const std::vector<float> odds = CategoryOdds(component_ids);
  if (odds.empty()) return std::nullopt;
  // Odds are the posterior over its maximum: the same argmax.
  CategoryClassifier::Probabilities p{};
  for (std::size_t k = 0; k < p.size() && k < odds.size(); ++k) p[k] = odds[k];
  const CategoryName name = recognition::NameCategory(p, votes, recognizer_.options().naming);
  if (!name.named) return std::nullopt;
  return name.category;
}

std::vector<segmentation::MatchResult> RecognizerComponentMatcher::MatchBatch(
    const std::vector<std::vector<std::int32_t>>& queries, segmentation::MatchScope scope) {
  if (!graph_) throw std::logic_error("RecognizerComponentMatcher: SetComponents was not called");
  if (recognizer_.options().compose_unions) DescribeMissing(queries);
  std::vector<segmentation::MatchResult> results(queries.size());
  ParallelForBlocks(static_cast<int>(queries.size()), threads_,
                         [&](int i) { results[i] = MatchDescribed(queries[i], scope); });
  return results;
}

}  // namespace objscan::recognition
