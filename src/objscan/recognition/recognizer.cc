#include "objscan/recognition/recognizer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "objscan/common/rng.h"
#include "objscan/recognition/keypoints.h"

namespace objscan::recognition {

void RecognitionOptions::Validate() const {
  config::Require(num_similar_models >= 1, "recognition.num_similar_models", "must be at least 1");
  config::Require(shortlist_size >= num_similar_models, "recognition.shortlist_size",
                  "must be >= num_similar_models");
  config::RequireNonNegative("recognition.bow_rank_weight", bow_rank_weight);
  alignment.Validate();
}

Recognizer::Recognizer(const ModelDatabase& database, const RecognitionOptions& options)
    : database_(database), options_(options) {
  options_.Validate();
  if (!database_.finalized()) throw std::invalid_argument("Recognizer: database not finalized");
  descriptor_ = MakeDescriptorExtractor(database_.settings().descriptor);
}

QueryDescription Recognizer::Describe(const geometry::PointCloud& query, const geometry::PointCloud* support) const {
  QueryDescription q;
  if (query.empty()) return q;
  const DatabaseSettings& s = database_.settings();
  Rng rng(s.keypoint_seed);  // fixed seed: the same points always get the same keypoints
  for (int i : SampleKeypointsLloyd(query.points, s.keypoints, &rng)) q.keypoints.push_back(query.points[i]);
  for (const auto& p : query.points) q.bounds.Extend(p.cast<double>());
  q.diagonal_m = q.bounds.Diagonal();
  std::vector<float> descriptors;
  descriptor_->Compute(support ? *support : query, q.keypoints, &descriptors);
  q.bow = ComputeSpatialBow(database_.vocabulary(), q.keypoints, descriptors, q.bounds, s.bow);
  return q;
}

std::vector<ScoredItem> Recognizer::Candidates(const QueryDescription& query, RetrievalScope scope, int count) const {
  return database_.index(scope).Query(query.bow, count);
}

SimilarModel Recognizer::Match(const QueryDescription& query, int entry) const {
  SimilarModel m;
  m.entry = entry;
  const AlignmentTarget& target = database_.keypoint_target(entry);
  m.alignment = AlignToItem(query.keypoints, target, options_.alignment);
  if (!m.alignment.ok()) return m;
  const Eigen::Affine3f T = m.alignment.T_item_query.cast<float>();
  std::vector<Eigen::Vector3f> c_in_m(query.keypoints.size());
  for (std::size_t i = 0; i < c_in_m.size(); ++i) c_in_m[i] = T * query.keypoints[i];
  const KdTree3 c_tree(c_in_m);
  const double diag = m.alignment.scale * query.diagonal_m;
  m.objectness = ComputeObjectness(c_in_m, c_tree, target.tree(), diag);
  m.fit = diag > 0.0 ? std::exp(-std::sqrt(m.objectness.similarity_m2) / diag) : 0.0;
  m.rank_score = m.fit;
  return m;
}

std::vector<SimilarModel> Recognizer::Retrieve(const QueryDescription& query, RetrievalScope scope) const {
  std::vector<SimilarModel> result;
  if (query.empty()) return result;
  const std::vector<ScoredItem> shortlist = Candidates(query, scope, options_.shortlist_size);
  result.reserve(shortlist.size());
  for (const ScoredItem& c : shortlist) {
    SimilarModel m = Match(query, c.item);
    m.bow_score = c.score;
    m.rank_score = std::pow(std::max(0.f, c.score), options_.bow_rank_weight) * m.fit;
    result.push_back(std::move(m));
  }
  std::stable_sort(result.begin(), result.end(),
                   [](const SimilarModel& a, const SimilarModel& b) { return a.rank_score > b.rank_score; });
  if (static_cast<int>(result.size()) > options_.num_similar_models) result.resize(options_.num_similar_models);
  return result;
}

}  // namespace objscan::recognition
