#include "objscan/segmentation/post_segmenter.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <string>

#include "objscan/common/config.h"
#include "objscan/common/error.h"
#include "objscan/common/union_find.h"

namespace objscan::segmentation {

void PostSegmenterOptions::Validate() const {
  config::RequireInRange("none_label_cost", none_label_cost, 0.0, 1.0);
  config::RequireInRange("complete_objectness", complete_objectness, 0.0, 1.0);
  config::RequireInRange("noise_objectness", noise_objectness, 0.0, 1.0);
  config::Require(noise_objectness <= complete_objectness, "noise_objectness",
                  "must not exceed complete_objectness");
  config::Require(smoothness == "paper" || smoothness == "gain", "smoothness", "must be paper or gain");
  config::RequireNonNegative("smoothness_scale", smoothness_scale);
  config::Require(gain_reference == "max" || gain_reference == "mean" || gain_reference == "min", "gain_reference",
                  "must be max, mean or min");
  config::RequireInRange("merge_min_gain", merge_min_gain, -1.0, 1.0);
  config::RequireInRange("object_merge_min_gain", object_merge_min_gain, -1.0, 1.0);
  alpha_expansion.Validate();
}

const char* ObjectStatusName(ObjectStatus status) {
  switch (status) {
    case ObjectStatus::kPartial:
      return "partial";
    case ObjectStatus::kComplete:
      return "complete";
    case ObjectStatus::kNoise:
      return "noise";
  }
  return "unknown";
}

namespace {

// Highest objectness in a match set (not relying on the matcher's order).
double MaxObjectness(const MatchResult& result) {
  double best = 0.0;
  for (const ModelMatch& m : result.models) best = std::max(best, m.objectness);
  return best;
}

bool IsLabelCategory(world::Category c) {
  const int id = world::CategoryId(c);
  return id >= 0 && id < world::kNumObjectCategories;
}


}  // namespace

PostSegmenter::PostSegmenter(PostSegmenterOptions options, ComponentMatcher* matcher)
    : options_(std::move(options)), matcher_(matcher) {
  options_.Validate();
  if (matcher_ == nullptr) throw InputError("PostSegmenter: matcher must not be null");
}

void PostSegmenter::ClearCache() {
  component_cache_.clear();
  pair_cache_.clear();
  group_cache_.clear();
}

PostSegmenter::GroupKey PostSegmenter::KeyOf(const PostSegmenterInput& input, const std::vector<int>& members) {
  GroupKey key;
  key.reserve(members.size());
  for (int i : members) {
    const auto& c = input.components[static_cast<std::size_t>(i)];
    key.emplace_back(c.id, c.revision);
  }
  std::sort(key.begin(), key.end());
  return key;
}

const MatchResult& PostSegmenter::GroupMatches(const PostSegmenterInput& input, const std::vector<int>& members,
                                               PostSegmenterStats* stats) {
  GroupKey key = KeyOf(input, members);
  auto it = group_cache_.find(key);
  if (it != group_cache_.end()) {
    if (stats != nullptr) ++stats->group_cache_hits;
    it->second.used = true;
    return it->second.result;
  }
  std::vector<std::int32_t> ids;
  ids.reserve(key.size());
  for (const auto& k : key) ids.push_back(k.first);
  if (stats != nullptr) ++stats->group_queries;
  GroupEntry entry;
  entry.result = matcher_->Match(ids, MatchScope::kFullModels);
  entry.used = true;
  return group_cache_.emplace(std::move(key), std::move(entry)).first->second.result;
}

void PostSegmenter::PrefetchGroups(const PostSegmenterInput& input, const std::vector<std::vector<int>>& unions,
                                   PostSegmenterStats* stats) {
  std::vector<GroupKey> missing;
  std::vector<std::vector<std::int32_t>> queries;
  for (const std::vector<int>& members : unions) {
    GroupKey key = KeyOf(input, members);
    auto it = group_cache_.find(key);
    if (it != group_cache_.end()) {
      ++stats->group_cache_hits;
      it->second.used = true;
      continue;
    }
    if (std::find(missing.begin(), missing.end(), key) != missing.end()) continue;
    std::vector<std::int32_t> ids;
    for (const auto& k : key) ids.push_back(k.first);
    queries.push_back(std::move(ids));
    missing.push_back(std::move(key));
  }
  if (queries.empty()) return;
  std::vector<MatchResult> results = matcher_->MatchBatch(queries, MatchScope::kFullModels);
  if (results.size() != queries.size()) throw InputError("PostSegmenter: matcher returned a wrong batch size");
  stats->group_queries += static_cast<int>(queries.size());
  for (std::size_t q = 0; q < missing.size(); ++q) {
    GroupEntry entry;
    entry.result = std::move(results[q]);
    entry.used = true;
    group_cache_[std::move(missing[q])] = std::move(entry);
  }
}

std::vector<std::vector<int>> PostSegmenter::SplitInstances(const PostSegmenterInput& input,
                                                            const std::vector<int>& members,
                                                            const std::vector<std::pair<int, int>>& group_edges,
                                                            const std::vector<double>& group_edge_weights,
                                                            PostSegmenterStats* stats) {
  if (members.size() < 2) return {members};
  const double whole = MaxObjectness(GroupMatches(input, members, stats));

  // Agglomerate parts along the group's edges, strongest pair objectness first, as long as merging
  // does not lower the objectness: parts of one object complete each other (objectness rises), two
  // objects merged look like neither (objectness drops).
  const int n = static_cast<int>(input.components.size());
  UnionFind parts(n);
  std::unordered_map<int, std::vector<int>> part_members;
  std::unordered_map<int, double> part_objectness;
  for (int i : members) {
    part_members[i] = {i};
    part_objectness[i] = MaxObjectness(GroupMatches(input, {i}, stats));
  }
  std::vector<std::size_t> order(group_edges.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    if (group_edge_weights[x] != group_edge_weights[y]) return group_edge_weights[x] > group_edge_weights[y];
    return group_edges[x] < group_edges[y];
  });
  for (std::size_t e : order) {
    const int ra = parts.Find(group_edges[e].first);
    const int rb = parts.Find(group_edges[e].second);
    if (ra == rb) continue;
    std::vector<int> merged = part_members[ra];
    merged.insert(merged.end(), part_members[rb].begin(), part_members[rb].end());
    std::sort(merged.begin(), merged.end());
    const double o = MaxObjectness(GroupMatches(input, merged, stats));
    if (o >= std::max(part_objectness[ra], part_objectness[rb])) {
      const int root = parts.Union(ra, rb);
      const int other = root == ra ? rb : ra;
      part_members.erase(other);
      part_objectness.erase(other);
      part_members[root] = std::move(merged);
      part_objectness[root] = o;
    }
  }
  if (part_members.size() < 2) return {members};
  double weakest = 1.0;
  for (const auto& [root, o] : part_objectness) weakest = std::min(weakest, o);
  if (!(weakest > whole)) return {members};
  std::vector<std::vector<int>> result;
  for (auto& [root, m] : part_members) result.push_back(std::move(m));
  std::sort(result.begin(), result.end());  // members are sorted indices: order by smallest index
  ++stats->splits;
  return result;
}

void PostSegmenter::MergeAdjacentObjects(const PostSegmenterInput& input, const std::vector<std::pair<int, int>>& edges,
                                         int none_label, std::vector<std::pair<std::vector<int>, int>>* objects,
                                         PostSegmenterStats* stats) {
  auto& objs = *objects;
  bool any_size = false;
  for (const auto& c : input.components) any_size = any_size || c.num_points > 0;
  auto size_of = [&](const std::vector<int>& members) {
    double n = 0.0;
    for (int i : members) n += any_size ? static_cast<double>(input.components[static_cast<std::size_t>(i)].num_points) : 1.0;
    return n;
  };
  std::vector<int> object_of(input.components.size(), -1);
  while (true) {
    for (std::size_t o = 0; o < objs.size(); ++o) {
      for (int i : objs[o].first) object_of[static_cast<std::size_t>(i)] = static_cast<int>(o);
    }
    // Adjacent pairs of labelled objects, each once.
    std::vector<std::pair<int, int>> pairs;
    for (const auto& [a, b] : edges) {
      int p = object_of[static_cast<std::size_t>(a)], q = object_of[static_cast<std::size_t>(b)];
      if (p == q || p < 0 || q < 0) continue;
      if (objs[static_cast<std::size_t>(p)].second == none_label || objs[static_cast<std::size_t>(q)].second == none_label) continue;
      pairs.emplace_back(std::min(p, q), std::max(p, q));
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    if (pairs.empty()) return;
    auto union_of = [&](int p, int q) {
      std::vector<int> m = objs[static_cast<std::size_t>(p)].first;
      m.insert(m.end(), objs[static_cast<std::size_t>(q)].first.begin(), objs[static_cast<std::size_t>(q)].first.end());
      std::sort(m.begin(), m.end());
      return m;
    };
    // Every object, then every adjacent pair's union (parallel to `pairs`), in one batch.
    std::vector<std::vector<int>> unions;
    for (const auto& o : objs) unions.push_back(o.first);
    for (const auto& [p, q] : pairs) unions.push_back(union_of(p, q));
    PrefetchGroups(input, unions, stats);
    double best_gain = -std::numeric_limits<double>::infinity();
    std::size_t best = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const auto& mp = objs[static_cast<std::size_t>(pairs[k].first)].first;
      const auto& mq = objs[static_cast<std::size_t>(pairs[k].second)].first;
      const double np = size_of(mp), nq = size_of(mq);
      const double fp = MaxObjectness(GroupMatches(input, mp, nullptr));
      const double fq = MaxObjectness(GroupMatches(input, mq, nullptr));
      const double fpq = MaxObjectness(GroupMatches(input, unions[objs.size() + k], nullptr));
      // With keep_larger_fit, the union must explain the larger part no worse than the larger
      // part's own model does: a well-explained object (0.94) does not absorb a badly explained
      // neighbour (0.83) because the neighbour's points gain more than its own lose.
      if (options_.object_merge_keep_larger_fit && fpq < (np >= nq ? fp : fq)) continue;
      const double gain = fpq - (np * fp + nq * fq) / std::max(1e-12, np + nq);
      if (gain > best_gain) {
        best_gain = gain;
        best = k;
      }
    }
    if (!(best_gain >= options_.object_merge_min_gain)) return;
    auto& keep = objs[static_cast<std::size_t>(pairs[best].first)];
    auto& gone = objs[static_cast<std::size_t>(pairs[best].second)];
    // The merged object keeps the label of its larger part.
    if (size_of(gone.first) > size_of(keep.first)) keep.second = gone.second;
    keep.first = std::move(unions[objs.size() + best]);
    objs.erase(objs.begin() + pairs[best].second);
    ++stats->object_merges;
  }
}

PostSegmentation PostSegmenter::Update(const PostSegmenterInput& input) {
  PostSegmentation out;
  PostSegmenterStats& stats = out.stats;
  const int n = static_cast<int>(input.components.size());

  // Index the components and normalise the edges (a < b by id, no duplicates).
  std::unordered_map<std::int32_t, int> index_of;
  index_of.reserve(input.components.size());
  for (int i = 0; i < n; ++i) {
    if (!index_of.emplace(input.components[static_cast<std::size_t>(i)].id, i).second) {
      throw InputError("PostSegmenter: duplicate component id " +
                       std::to_string(input.components[static_cast<std::size_t>(i)].id));
    }
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> edge_ids;
  edge_ids.reserve(input.edges.size());
  for (auto [a, b] : input.edges) {
    if (a == b) throw InputError("PostSegmenter: self-adjacent component " + std::to_string(a));
    if (!index_of.count(a) || !index_of.count(b)) {
      throw InputError("PostSegmenter: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                       ") names an unknown component");
    }
    edge_ids.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(edge_ids.begin(), edge_ids.end());
  edge_ids.erase(std::unique(edge_ids.begin(), edge_ids.end()), edge_ids.end());

  for (auto& [id, e] : component_cache_) e.used = false;
  for (auto& [key, e] : pair_cache_) e.used = false;
  for (auto& [key, e] : group_cache_) e.used = false;

  // M(c) for every component, querying only new or changed ones (one batch).
  std::vector<const MatchResult*> component_matches(static_cast<std::size_t>(n), nullptr);
  {
    std::vector<int> missing;
    for (int i = 0; i < n; ++i) {
      const auto& c = input.components[static_cast<std::size_t>(i)];
      auto it = component_cache_.find(c.id);
      if (it != component_cache_.end() && it->second.revision == c.revision) {
        ++stats.component_cache_hits;
        it->second.used = true;
        component_matches[static_cast<std::size_t>(i)] = &it->second.result;
      } else {
        missing.push_back(i);
      }
    }
    std::vector<std::vector<std::int32_t>> queries;
    for (int i : missing) queries.push_back({input.components[static_cast<std::size_t>(i)].id});
    std::vector<MatchResult> results =
        queries.empty() ? std::vector<MatchResult>{} : matcher_->MatchBatch(queries, MatchScope::kAllEntries);
    if (results.size() != queries.size()) throw InputError("PostSegmenter: matcher returned a wrong batch size");
    stats.component_queries = static_cast<int>(queries.size());
    for (std::size_t q = 0; q < missing.size(); ++q) {
      const auto& c = input.components[static_cast<std::size_t>(missing[q])];
      ComponentEntry& entry = component_cache_[c.id];
      entry.revision = c.revision;
      entry.result = std::move(results[q]);
      entry.used = true;
      component_matches[static_cast<std::size_t>(missing[q])] = &entry.result;
    }
  }

  // The smoothness weights: eq. (4) from M(c u d) over all entries ("paper"), or the full-model
  // objectness gain of each adjacent union over its parts ("gain").
  const bool gain_mode = options_.smoothness == "gain";
  std::vector<double> edge_weight(edge_ids.size(), 0.0);
  std::vector<char> edge_cut(edge_ids.size(), 0);
  if (options_.graph_cuts && gain_mode) {
    std::vector<std::vector<int>> unions;
    unions.reserve(static_cast<std::size_t>(n) + edge_ids.size());
    for (int i = 0; i < n; ++i) unions.push_back({i});
    for (const auto& [a, b] : edge_ids) unions.push_back({index_of[a], index_of[b]});
    PrefetchGroups(input, unions, &stats);
    for (std::size_t e = 0; e < edge_ids.size(); ++e) {
      const int a = index_of[edge_ids[e].first];
      const int b = index_of[edge_ids[e].second];
      const double fa = MaxObjectness(GroupMatches(input, {a}, nullptr));
      const double fb = MaxObjectness(GroupMatches(input, {b}, nullptr));
      const double fab = MaxObjectness(GroupMatches(input, {a, b}, nullptr));
      const double reference = options_.gain_reference == "max"    ? std::max(fa, fb)
                               : options_.gain_reference == "min" ? std::min(fa, fb)
                                                                  : 0.5 * (fa + fb);
      const double gain = fab - reference;
      edge_weight[e] = options_.smoothness_scale * std::max(0.0, gain);
      edge_cut[e] = gain < options_.merge_min_gain ? 1 : 0;
    }
  }
  if (options_.graph_cuts && !gain_mode) {
    std::vector<std::size_t> missing;
    for (std::size_t e = 0; e < edge_ids.size(); ++e) {
      const auto& ca = input.components[static_cast<std::size_t>(index_of[edge_ids[e].first])];
      const auto& cb = input.components[static_cast<std::size_t>(index_of[edge_ids[e].second])];
      auto it = pair_cache_.find(edge_ids[e]);
      if (it != pair_cache_.end() && it->second.revision_a == ca.revision && it->second.revision_b == cb.revision) {
        ++stats.pair_cache_hits;
        it->second.used = true;
        edge_weight[e] = MaxObjectness(it->second.result);
      } else {
        missing.push_back(e);
      }
    }
    std::vector<std::vector<std::int32_t>> queries;
    for (std::size_t e : missing) queries.push_back({edge_ids[e].first, edge_ids[e].second});
    std::vector<MatchResult> results =
        queries.empty() ? std::vector<MatchResult>{} : matcher_->MatchBatch(queries, MatchScope::kAllEntries);
    if (results.size() != queries.size()) throw InputError("PostSegmenter: matcher returned a wrong batch size");
    stats.pair_queries = static_cast<int>(queries.size());
    for (std::size_t q = 0; q < missing.size(); ++q) {
      const std::size_t e = missing[q];
      PairEntry& entry = pair_cache_[edge_ids[e]];
      entry.revision_a = input.components[static_cast<std::size_t>(index_of[edge_ids[e].first])].revision;
      entry.revision_b = input.components[static_cast<std::size_t>(index_of[edge_ids[e].second])].revision;
      entry.result = std::move(results[q]);
      entry.used = true;
      edge_weight[e] = MaxObjectness(entry.result);
    }
  }

  // Labels: the categories present in some M(c), ascending, then "none". A category absent from every
  // M(c) costs 1 everywhere, which "none" (cost <= 1) dominates, so leaving it out loses nothing.
  std::vector<int> label_of_category(world::kNumObjectCategories, -1);
  for (const MatchResult* r : component_matches) {
    for (const ModelMatch& m : r->models) {
      if (IsLabelCategory(m.category)) label_of_category[static_cast<std::size_t>(world::CategoryId(m.category))] = 0;
    }
  }
  std::vector<world::Category> label_category;
  for (int c = 0; c < world::kNumObjectCategories; ++c) {
    if (label_of_category[static_cast<std::size_t>(c)] >= 0) {
      label_of_category[static_cast<std::size_t>(c)] = static_cast<int>(label_category.size());
      label_category.push_back(static_cast<world::Category>(c));
    }
  }
  const int none_label = static_cast<int>(label_category.size());
  const int num_labels = none_label + 1;
  stats.num_labels = num_labels;

  PottsEnergy energy(n, num_labels);
  for (int i = 0; i < n; ++i) {
    for (int l = 0; l < none_label; ++l) energy.SetDataCost(i, l, 1.0);
    energy.SetDataCost(i, none_label, options_.none_label_cost);
    for (const ModelMatch& m : component_matches[static_cast<std::size_t>(i)]->models) {
      if (!IsLabelCategory(m.category)) continue;
      const int l = label_of_category[static_cast<std::size_t>(world::CategoryId(m.category))];
      const double cost = std::clamp(1.0 - m.objectness, 0.0, 1.0);
      if (cost < energy.DataCost(i, l)) energy.SetDataCost(i, l, cost);
    }
  }
  for (std::size_t e = 0; e < edge_ids.size(); ++e) {
    energy.AddEdge(index_of[edge_ids[e].first], index_of[edge_ids[e].second], std::max(0.0, edge_weight[e]));
  }
  const AlphaExpansionResult solution = MinimizeByAlphaExpansion(energy, options_.alpha_expansion);
  out.energy = solution.energy;
  out.solver_status = solution.status;

  // Objects: connected groups of equally labelled components ("none" components stay single).
  UnionFind groups(n);
  for (std::size_t e = 0; e < edge_ids.size(); ++e) {
    const int a = index_of[edge_ids[e].first];
    const int b = index_of[edge_ids[e].second];
    const int la = n > 0 ? solution.labels[static_cast<std::size_t>(a)] : 0;
    // Without graph cuts (the pre-segmentation baseline) every component stays an object of its own.
    if (options_.graph_cuts && !edge_cut[e] && la != none_label && la == solution.labels[static_cast<std::size_t>(b)]) {
      groups.Union(a, b);
    }
  }
  std::map<int, std::vector<int>> members_of_root;
  for (int i = 0; i < n; ++i) members_of_root[groups.Find(i)].push_back(i);
  std::map<int, std::vector<std::size_t>> edges_of_root;
  for (std::size_t e = 0; e < edge_ids.size(); ++e) {
    const int a = index_of[edge_ids[e].first];
    const int b = index_of[edge_ids[e].second];
    if (!edge_cut[e] && groups.Find(a) == groups.Find(b)) edges_of_root[groups.Find(a)].push_back(e);
  }

  std::vector<std::pair<std::vector<int>, int>> parts;  // (member indices, graph-cut label)
  for (auto& [root, members] : members_of_root) {
    const int label = solution.labels[static_cast<std::size_t>(root)];
    if (options_.split_instances && members.size() >= 2) {
      std::vector<std::pair<int, int>> group_edges;
      std::vector<double> group_weights;
      for (std::size_t e : edges_of_root[root]) {
        group_edges.emplace_back(index_of[edge_ids[e].first], index_of[edge_ids[e].second]);
        group_weights.push_back(edge_weight[e]);
      }
      for (auto& part : SplitInstances(input, members, group_edges, group_weights, &stats)) {
        parts.emplace_back(std::move(part), label);
      }
    } else {
      parts.emplace_back(members, label);
    }
  }

  if (options_.graph_cuts && options_.merge_objects) {
    std::vector<std::pair<int, int>> edges;
    edges.reserve(edge_ids.size());
    for (const auto& [a, b] : edge_ids) edges.emplace_back(index_of[a], index_of[b]);
    MergeAdjacentObjects(input, edges, none_label, &parts, &stats);
  }

  out.object_of_component.assign(static_cast<std::size_t>(n), -1);
  out.category_of_component.assign(static_cast<std::size_t>(n), std::nullopt);
  std::vector<PostSegmentedObject> objects;
  objects.reserve(parts.size());
  for (auto& [members, label] : parts) {
    PostSegmentedObject object;
    if (label != none_label) object.category = label_category[static_cast<std::size_t>(label)];
    object.full_model_matches = GroupMatches(input, members, &stats);
    object.objectness = MaxObjectness(object.full_model_matches);
    if (object.objectness < options_.noise_objectness) {
      object.status = ObjectStatus::kNoise;
    } else if (object.objectness > options_.complete_objectness) {
      object.status = ObjectStatus::kComplete;
    } else {
      object.status = ObjectStatus::kPartial;
    }
    for (int i : members) object.component_ids.push_back(input.components[static_cast<std::size_t>(i)].id);
    std::sort(object.component_ids.begin(), object.component_ids.end());
    objects.push_back(std::move(object));
  }
  std::sort(objects.begin(), objects.end(), [](const PostSegmentedObject& a, const PostSegmentedObject& b) {
    return a.component_ids.front() < b.component_ids.front();
  });
  for (std::size_t o = 0; o < objects.size(); ++o) {
    for (std::int32_t id : objects[o].component_ids) {
      const int i = index_of[id];
      out.object_of_component[static_cast<std::size_t>(i)] = static_cast<int>(o);
      out.category_of_component[static_cast<std::size_t>(i)] = objects[o].category;
    }
  }
  out.objects = std::move(objects);

  // Keep only what this step used: removed components and stale unions leave the cache.
  for (auto it = component_cache_.begin(); it != component_cache_.end();) {
    it = it->second.used ? std::next(it) : component_cache_.erase(it);
  }
  for (auto it = pair_cache_.begin(); it != pair_cache_.end();) {
    it = it->second.used ? std::next(it) : pair_cache_.erase(it);
  }
  for (auto it = group_cache_.begin(); it != group_cache_.end();) {
    it = it->second.used ? std::next(it) : group_cache_.erase(it);
  }
  return out;
}

}  // namespace objscan::segmentation
