#pragma once
// Post-segmentation by multi-class graph cuts (paper §4.3 and the objectness thresholds of §6.1):
// labels every pre-segmented component c with a category (or "none") by minimizing
//
//   E(L) = sum_c E_D(l_c) + sum_(c,d) E_S(l_c, l_d)                                  eq. (2)
//   E_D(l_c) = min over m in M(c), L(m) = l_c of (1 - O(c, m)); 1 when there is none  eq. (3)
//   E_S(l_c, l_d) = [l_c != l_d] max over m in M(c u d) of O(c u d, m)               eq. (4)
//
// with alpha-expansion, then groups connected equally-labelled components into objects R and grades
// them by O(r) = max over full models of O(r, m): noise below noise_objectness, complete above
// complete_objectness (to be replaced by the best model, placed with its alignment).
//
// Beyond the paper: (1) a "none" label with a constant data cost for components that match nothing;
// (2) optional instance splitting (split_instances): a connected same-label group is split into parts
// when every part has higher objectness than the whole, so two touching chairs stay two chairs;
// (3) matcher results are cached per component, per adjacent pair and per group, keyed by component
// id and revision, so a step only queries what changed.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "objscan/segmentation/alpha_expansion.h"
#include "objscan/segmentation/post_matcher.h"
#include "objscan/world/category.h"

namespace objscan::segmentation {

class ComponentGraph;

struct PostSegmenterOptions {
  // Data cost of the "none" label; in [0, 1] (a category absent from M(c) costs 1). The default makes
  // a component whose best match has objectness below 0.05 (the noise threshold) prefer "none".
  double none_label_cost = 0.95;
  // O(r) above this: complete object, replaced by its best full model (paper: 0.96).
  double complete_objectness = 0.96;
  // O(r) below this: noise, removed from the scene surface T (paper: 0.05).
  double noise_objectness = 0.05;
  // Split connected same-label groups into instances when every part has a higher objectness than the
  // whole. false = the paper's behaviour (one object per connected same-label group).
  bool split_instances = true;
  // false: the pre-segmentation baseline (Tateno et al.): each component is recognized on its own
  // (its best M(c)), no smoothness term, no merging.
  bool graph_cuts = true;
  // Smoothness weight w(c, d) of an adjacent pair, paid when their labels differ:
  //  "paper": eq. (4), w = max over m in M(c u d) of O(c u d, m) over all database entries.
  //  "gain":  w = smoothness_scale * max(0, G(c, d)) with the full-model objectness gain
  //           G(c, d) = F(c u d) - max(F(c), F(d)), F(X) = max over full models m of O(X, m); and an
  //           edge with G(c, d) < merge_min_gain never joins an object, whatever the labels.
  // Why "gain": eq. (1) divides by Diag(X), so any large union scores O ~ 0.8-0.9 against some entry
  // (components and pairs included) and eq. (4) glues whole regions together (a bed absorbs the
  // dresser through undetected wall strips). Whether the union is more of a whole object than its
  // parts separates parts of one object from neighbouring objects much better (measured on
  // procedural rooms, see scanning/postseg_rooms_test.cc).
  std::string smoothness = "gain";
  double smoothness_scale = 1.0;  // gain mode: lambda
  double merge_min_gain = 0.0;    // gain mode: edges with a lower gain are cut
  // gain mode: what the union is compared with, "max" = max(F(c), F(d)), "mean" = their mean
  // weighted by nothing, "min" = min(F(c), F(d)).
  std::string gain_reference = "max";
  // Beyond the paper: after the graph cut, adjacent objects merge, best first, while the union's
  // full-model objectness exceeds the point-weighted mean of theirs by at least object_merge_min_gain.
  // Pairwise component tests miss objects of three or more parts, and a small fragment scores high
  // against a small model (a lamp's stem as a radio), which blocks every pairwise merge with it.
  // false = the paper (objects are the graph cut's groups). A gain of 0 merges whenever the union
  // explains the points at least as well as its parts: on real furniture a piece (a desk's half, a
  // sofa's cushion) rarely reaches a model's objectness alone, and a positive gain left those pieces
  // apart, each becoming an object of interest of its own (OASC dev: precision +7-8 points, NBOs
  // -25%; docs/results/oasc-dev-2026-11-26-loop-objects-of-interest.md).
  bool merge_objects = true;
  double object_merge_min_gain = 0.0;
  // And the union's objectness must be at least that of its larger part (by points): a
  // well-explained object does not absorb a badly explained neighbour. Off: on the OASC dev rooms it
  // blocks more useful merges than harmful ones (built-in database precision 34.2 -> 30.6, NBOs
  // 37.6 -> 48.5; docs/results/oasc-dev-2026-11-26-loop-objects-of-interest.md).
  bool object_merge_keep_larger_fit = false;
  AlphaExpansionOptions alpha_expansion;

  template <class V>
  void Visit(V& v) {
    v("none_label_cost", none_label_cost);
    v("complete_objectness", complete_objectness);
    v("noise_objectness", noise_objectness);
    v("split_instances", split_instances);
    v("graph_cuts", graph_cuts);
    v("smoothness", smoothness);
    v("smoothness_scale", smoothness_scale);
    v("merge_min_gain", merge_min_gain);
    v("gain_reference", gain_reference);
    v("merge_objects", merge_objects);
    v("object_merge_min_gain", object_merge_min_gain);
    v("object_merge_keep_larger_fit", object_merge_keep_larger_fit);
    v("alpha_expansion", alpha_expansion);
  }
  void Validate() const;
};

// What the post-segmenter needs of the component graph: ids, revisions and adjacency.
struct PostSegmenterInput {
  struct Component {
    std::int32_t id = 0;          // ComponentGraph's Component::label
    std::uint64_t revision = 0;   // changes whenever the component's points change
    std::size_t num_points = 0;   // its size (weights objects in merge_objects; 0 = all weigh 1)
  };
  std::vector<Component> components;                        // ids unique
  std::vector<std::pair<std::int32_t, std::int32_t>> edges; // adjacent component ids, a != b

  static PostSegmenterInput FromGraph(const ComponentGraph& graph);
};

enum class ObjectStatus {
  kPartial,   // noise_objectness <= O(r) <= complete_objectness: keep scanning it
  kComplete,  // O(r) > complete_objectness: replace by the best full model
  kNoise,     // O(r) < noise_objectness: remove from T
};
const char* ObjectStatusName(ObjectStatus status);

// One r in R.
struct PostSegmentedObject {
  std::vector<std::int32_t> component_ids;   // ascending
  std::optional<world::Category> category;   // the graph-cut label; nullopt for "none"
  double objectness = 0.0;                   // O(r) = max over full models m of O(r, m)
  ObjectStatus status = ObjectStatus::kNoise;
  MatchResult full_model_matches;            // M(r) over full models, best first (NBV shape priors)

  // The model replacing a complete object (with its T_world_model), nullptr when there is none.
  const ModelMatch* best_model() const {
    return full_model_matches.models.empty() ? nullptr : &full_model_matches.models.front();
  }
};

// Matcher use of one Update.
struct PostSegmenterStats {
  int component_queries = 0;   // M(c) computed (cache misses)
  int pair_queries = 0;        // M(c u d) computed
  int group_queries = 0;       // M(r) over full models computed (objects and split candidates)
  int component_cache_hits = 0;
  int pair_cache_hits = 0;
  int group_cache_hits = 0;
  int num_labels = 0;          // labels in the graph cut (categories present in some M(c), plus none)
  int splits = 0;              // same-label groups split into instances
  int object_merges = 0;       // adjacent objects merged (merge_objects)
};

struct PostSegmentation {
  std::vector<PostSegmentedObject> objects;  // ordered by smallest component id
  // Parallel to input.components: index into objects, and the chosen category (nullopt = none).
  std::vector<int> object_of_component;
  std::vector<std::optional<world::Category>> category_of_component;
  double energy = 0.0;                       // E(L) of the labeling, eq. (2)
  AlphaExpansionStatus solver_status = AlphaExpansionStatus::kEmpty;
  PostSegmenterStats stats;
};

class PostSegmenter {
 public:
  // `matcher` is not owned and must outlive the segmenter. Throws ConfigError on invalid options.
  PostSegmenter(PostSegmenterOptions options, ComponentMatcher* matcher);

  // One post-segmentation of the current components. Queries the matcher only for components, pairs
  // and groups whose (id, revision) content is not cached; entries unused by this step are dropped.
  // Throws InputError on duplicate component ids or edges naming unknown components.
  PostSegmentation Update(const PostSegmenterInput& input);

  // Forget every cached match (e.g. after the database changed).
  void ClearCache();

  const PostSegmenterOptions& options() const { return options_; }

 private:
  // (id, revision) of each member, ascending by id: the cache key of a union of components.
  using GroupKey = std::vector<std::pair<std::int32_t, std::uint64_t>>;
  // The cache key of a union of components (by index into the input).
  static GroupKey KeyOf(const PostSegmenterInput& input, const std::vector<int>& members);

  struct ComponentEntry {
    std::uint64_t revision = 0;
    MatchResult result;
    bool used = false;
  };
  struct PairEntry {
    std::uint64_t revision_a = 0;
    std::uint64_t revision_b = 0;
    MatchResult result;
    bool used = false;
  };
  struct GroupEntry {
    MatchResult result;
    bool used = false;
  };

  // Full-model matches of the union of components (by index into the current input).
  const MatchResult& GroupMatches(const PostSegmenterInput& input, const std::vector<int>& members,
                                  PostSegmenterStats* stats);
  // Fills the group cache for these unions (indices into the current input) with one batch query.
  void PrefetchGroups(const PostSegmenterInput& input, const std::vector<std::vector<int>>& unions,
                      PostSegmenterStats* stats);
  // merge_objects: merges adjacent objects (member indices, graph-cut label) in place.
  void MergeAdjacentObjects(const PostSegmenterInput& input, const std::vector<std::pair<int, int>>& edges,
                            int none_label, std::vector<std::pair<std::vector<int>, int>>* objects,
                            PostSegmenterStats* stats);
  // Splits a same-label group into instances; returns its parts (one part = no split).
  std::vector<std::vector<int>> SplitInstances(const PostSegmenterInput& input, const std::vector<int>& members,
                                               const std::vector<std::pair<int, int>>& group_edges,
                                               const std::vector<double>& group_edge_weights,
                                               PostSegmenterStats* stats);

  PostSegmenterOptions options_;
  ComponentMatcher* matcher_;
  std::unordered_map<std::int32_t, ComponentEntry> component_cache_;
  std::map<std::pair<std::int32_t, std::int32_t>, PairEntry> pair_cache_;
  std::map<GroupKey, GroupEntry> group_cache_;
};

}  // namespace objscan::segmentation
