#pragma once
// segmentation::ComponentMatcher backed by a Recognizer: M(X) and O(X, m) for unions X of the
// pre-segmented components of the current ComponentGraph (the seam the post-segmenter talks to).
#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "objscan/recognition/recognizer.h"
#include "objscan/segmentation/component_graph.h"
#include "objscan/segmentation/post_matcher.h"

namespace objscan::recognition {

class RecognizerComponentMatcher : public segmentation::ComponentMatcher {
 public:
  // `recognizer` must outlive the matcher; `threads` for MatchBatch (0 = all cores; same results).
  explicit RecognizerComponentMatcher(const Recognizer& recognizer, int threads = 0)
      : recognizer_(recognizer), threads_(threads) {}

  // The graph whose components the ids refer to; must stay valid while matching (set every step).
  // Cached descriptions of components that are gone or changed since are dropped.
  void SetComponents(const segmentation::ComponentGraph* graph);
  // What the map says about space (null = nothing); must stay valid while matching (set every step).
  void SetSpaceEvidence(const SpaceEvidence* space) { space_ = space; }

  segmentation::MatchResult Match(const std::vector<std::int32_t>& component_ids,
                                  segmentation::MatchScope scope) override;
  std::vector<segmentation::MatchResult> MatchBatch(const std::vector<std::vector<std::int32_t>>& queries,
                                                    segmentation::MatchScope scope) override;

  // The best full model of `category` for the union: every full-model entry of that category is
  // aligned to it and measured (not only those the bag of words shortlists). Nullopt when the
  // database holds no such model or the union has no description. For context that names the
  // category (an object in a wall opening is a window) but not the model or its pose.
  std::optional<segmentation::ModelMatch> BestOfCategory(const std::vector<std::int32_t>& component_ids,
                                                         world::Category category);
  // Recognizer::CategoryOdds of the union's description (empty when it has none).
  std::vector<float> CategoryOdds(const std::vector<std::int32_t>& component_ids);
  // The category the union is named by from the classifier and `votes` (its models' categories and
  // scores) with RecognitionOptions::naming (category_naming.h); nullopt without a description.
  std::optional<world::Category> NameCategory(const std::vector<std::int32_t>& component_ids,
                                              const std::vector<RetrievedCategory>& votes);

 private:
  // Describes (in parallel) every component named in `queries` whose description is not cached at
  // its current revision; only with RecognitionOptions::compose_unions.
  void DescribeMissing(const std::vector<std::vector<std::int32_t>>& queries);
  // M(X) once DescribeMissing covered X (reads the cache only, so batch queries may run in parallel).
  segmentation::MatchResult MatchDescribed(const std::vector<std::int32_t>& component_ids,
                                           segmentation::MatchScope scope) const;
  // The description of the union: a cached one, one composed into *storage, or (without
  // compose_unions) one described into *storage. Null when the union has no points.
  const QueryDescription* DescribedQuery(const std::vector<std::int32_t>& component_ids,
                                         QueryDescription* storage) const;

  struct CachedDescription {
    std::uint64_t revision = 0;
    std::shared_ptr<const QueryDescription> description;
  };
  const Recognizer& recognizer_;
  std::unordered_map<std::int32_t, CachedDescription> descriptions_;  // by component id
  int threads_ = 0;
  const segmentation::ComponentGraph* graph_ = nullptr;
  const SpaceEvidence* space_ = nullptr;
};

}  // namespace objscan::recognition
