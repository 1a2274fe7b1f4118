#pragma once
// segmentation::ComponentMatcher backed by a Recognizer: M(X) and O(X, m) for unions X of the
// pre-segmented components of the current ComponentGraph (the seam the post-segmenter talks to).
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
  void SetComponents(const segmentation::ComponentGraph* graph) { graph_ = graph; }

  segmentation::MatchResult Match(const std::vector<std::int32_t>& component_ids,
                                  segmentation::MatchScope scope) override;
  std::vector<segmentation::MatchResult> MatchBatch(const std::vector<std::vector<std::int32_t>>& queries,
                                                    segmentation::MatchScope scope) override;

 private:
  const Recognizer& recognizer_;
  int threads_ = 0;
  const segmentation::ComponentGraph* graph_ = nullptr;
};

}  // namespace objscan::recognition
