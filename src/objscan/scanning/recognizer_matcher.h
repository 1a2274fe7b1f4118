#pragma once
// Implements the post-segmenter's seam (segmentation::ComponentMatcher) with the recognizer: the union
// of the asked components' points is described like the database entries and M(X) retrieved, aligned
// and scored with eq. (1). Queries of one batch run in parallel; each result depends only on its query.
#include <Eigen/Geometry>
#include <vector>

#include "objscan/recognition/recognizer.h"
#include "objscan/segmentation/component_graph.h"
#include "objscan/segmentation/post_matcher.h"

namespace objscan::scanning {

class RecognizerMatcher : public segmentation::ComponentMatcher {
 public:
  // Both must outlive the matcher; `threads` 0 = hardware concurrency.
  RecognizerMatcher(const recognition::Recognizer& recognizer, int threads);

  // The graph the component ids refer to (set before each post-segmenter update).
  void set_graph(const segmentation::ComponentGraph* graph) { graph_ = graph; }

  segmentation::MatchResult Match(const std::vector<std::int32_t>& component_ids,
                                  segmentation::MatchScope scope) override;
  std::vector<segmentation::MatchResult> MatchBatch(const std::vector<std::vector<std::int32_t>>& queries,
                                                    segmentation::MatchScope scope) override;

  // Queries answered since construction.
  long num_queries() const { return num_queries_; }

 private:
  const recognition::Recognizer& recognizer_;
  const segmentation::ComponentGraph* graph_ = nullptr;
  int threads_;
  long num_queries_ = 0;
};

// Rigid part of an alignment (rotation about Z and translation); the uniform scale is returned apart.
geometry::Pose3 RigidPart(const Eigen::Affine3d& T, double* scale);

}  // namespace objscan::scanning
