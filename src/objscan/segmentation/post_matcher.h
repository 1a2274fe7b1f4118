#pragma once
// The seam between post-segmentation and recognition. Segmentation comes before recognition in the
// module order, so the post-segmenter talks to the model database only through this interface;
// recognition implements it (retrieval of the top-n_s similar entries M(X), objectness O(X, m) of the
// paper's eq. (1), and the alignment of each entry onto X).
#include <cstdint>
#include <vector>

#include "objscan/geometry/pose.h"
#include "objscan/world/category.h"

namespace objscan::segmentation {

// Which database entries a query is compared with (paper §6.1 "Selection of similar model sets"):
// components and adjacent pairs against every entry (full models, their components and their
// adjacent pairs), post-segmented objects against full models only.
enum class MatchScope { kAllEntries, kFullModels };

// One m in M(X).
struct ModelMatch {
  int entry_id = -1;                                  // database entry (full model, component or pair)
  int model_id = -1;                                  // the source model the entry belongs to
  world::Category category = world::Category::kOther; // L(m)
  bool full_model = false;                            // the entry is a whole model
  double objectness = 0.0;                            // O(X, m) in [0, 1]
  // Alignment of the entry onto X: maps the entry's model frame into the world. Must be filled at
  // least for the best match; a complete object is replaced by its best model placed with it.
  geometry::Pose3 T_world_model = geometry::Pose3::Identity();
};

// M(X): at most n_s matches, best (highest objectness) first; empty when nothing is similar.
struct MatchResult {
  std::vector<ModelMatch> models;

  double BestObjectness() const { return models.empty() ? 0.0 : models.front().objectness; }
};

class ComponentMatcher {
 public:
  virtual ~ComponentMatcher() = default;
  // M(X) for X = the union of the given pre-segmented components (ids as in ComponentGraph, i.e.
  // Component::label; ascending, no duplicates). Called only for what changed since the last step;
  // the post-segmenter caches the results.
  virtual MatchResult Match(const std::vector<std::int32_t>& component_ids, MatchScope scope) = 0;

  // Many queries at once, so an implementation can spread them over threads; results[i] answers
  // queries[i] and must equal Match(queries[i], scope) (same result whatever the thread count).
  virtual std::vector<MatchResult> MatchBatch(const std::vector<std::vector<std::int32_t>>& queries,
                                              MatchScope scope) {
    std::vector<MatchResult> results;
    results.reserve(queries.size());
    for (const auto& q : queries) results.push_back(Match(q, scope));
    return results;
  }
};

}  // namespace objscan::segmentation
