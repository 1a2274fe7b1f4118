#include "objscan/scanning/recognizer_matcher.h"

#include "objscan/common/error.h"
#include "objscan/sim/parallel_for.h"

namespace objscan::scanning {

RecognizerMatcher::RecognizerMatcher(const recognition::Recognizer& recognizer, int threads)
    : recognizer_(recognizer), threads_(threads) {}

geometry::Pose3 RigidPart(const Eigen::Affine3d& T, double* scale) {
  const Eigen::Matrix3d L = T.linear();
  const double s = std::cbrt(std::max(1e-12, std::abs(L.determinant())));
  if (scale) *scale = s;
  geometry::Pose3 rigid = geometry::Pose3::Identity();
  // Orthonormalise (the linear part is s * R up to round-off).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(L / s, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0) R = -R;
  rigid.linear() = R;
  rigid.translation() = T.translation();
  return rigid;
}

segmentation::MatchResult RecognizerMatcher::Match(const std::vector<std::int32_t>& component_ids,
                                                   segmentation::MatchScope scope) {
  return MatchBatch({component_ids}, scope).front();
}

std::vector<segmentation::MatchResult> RecognizerMatcher::MatchBatch(
    const std::vector<std::vector<std::int32_t>>& queries, segmentation::MatchScope scope) {
  if (graph_ == nullptr) throw std::logic_error("RecognizerMatcher: no component graph set");
  std::vector<segmentation::MatchResult> results(queries.size());
  const auto retrieval_scope = scope == segmentation::MatchScope::kFullModels
                                   ? recognition::RetrievalScope::kFullModels
                                   : recognition::RetrievalScope::kAllEntries;
  const auto& entries = recognizer_.database().entries();
  sim::ParallelForBlocks(static_cast<int>(queries.size()), threads_, [&](int q) {
    geometry::PointCloud cloud;
    for (std::int32_t id : queries[q]) {
      const segmentation::Component* c = graph_->Find(id);
      if (c == nullptr) continue;
      cloud.points.insert(cloud.points.end(), c->points.begin(), c->points.end());
      cloud.normals.insert(cloud.normals.end(), c->normals.begin(), c->normals.end());
    }
    if (cloud.points.empty()) return;
    const recognition::QueryDescription description = recognizer_.Describe(cloud);
    if (description.empty()) return;
    const std::vector<recognition::SimilarModel> similar = recognizer_.Retrieve(description, retrieval_scope);
    auto& out = results[q].models;
    out.reserve(similar.size());
    for (const auto& s : similar) {
      if (!s.alignment.ok()) continue;
      const auto& entry = entries[s.entry];
      segmentation::ModelMatch m;
      m.entry_id = s.entry;
      m.model_id = entry.model_index;
      m.category = entry.category;
      m.full_model = entry.kind == recognition::EntryKind::kFullModel;
      m.objectness = s.objectness.objectness;
      m.T_world_model = RigidPart(s.T_world_model(), nullptr);
      out.push_back(m);
    }
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.objectness > b.objectness; });
  });
  num_queries_ += static_cast<long>(queries.size());
  return results;
}

}  // namespace objscan::scanning
