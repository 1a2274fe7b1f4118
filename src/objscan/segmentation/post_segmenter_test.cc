#include "objscan/segmentation/post_segmenter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/common/error.h"
#include "objscan/segmentation/component_graph.h"

namespace objscan::segmentation {
namespace {

using world::Category;

// A matcher built from analytic objectness tables over a known scene: each true object is a set of
// component ids with a category, a model and a pose.
//   Full models: O(S) = 0.98 * similarity^2 * completeness, with similarity = |S n k| / |S| and
//   completeness = |S n k| / |k| for the object k sharing most components with S.
//   All entries (components and adjacent pairs are in the database): O(S) = part_objectness when S
//   lies inside one object, 0.8 * similarity^2 otherwise.
// Explicit table entries for the all-entries scope override the analytic rule.
class FakeMatcher : public ComponentMatcher {
 public:
  struct TrueObject {
    std::vector<std::int32_t> components;
    Category category;
    int model_id;
  };

  explicit FakeMatcher(std::vector<TrueObject> objects) : objects_(std::move(objects)) {}

  void SetAllEntries(std::vector<std::int32_t> ids, std::vector<std::pair<Category, double>> matches) {
    std::sort(ids.begin(), ids.end());
    MatchResult r;
    for (auto [category, o] : matches) {
      ModelMatch m;
      m.category = category;
      m.objectness = o;
      r.models.push_back(m);
    }
    std::sort(r.models.begin(), r.models.end(),
              [](const ModelMatch& a, const ModelMatch& b) { return a.objectness > b.objectness; });
    table_[ids] = r;
  }

  MatchResult Match(const std::vector<std::int32_t>& ids, MatchScope scope) override {
    EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
    if (scope == MatchScope::kAllEntries) {
      ++all_calls;
      if (ids.size() == 1) ++component_calls;
      if (ids.size() == 2) ++pair_calls;
      auto it = table_.find(ids);
      if (it != table_.end()) return it->second;
    } else {
      ++full_calls;
    }
    int best = -1;
    int best_shared = 0;
    for (std::size_t k = 0; k < objects_.size(); ++k) {
      int shared = 0;
      for (std::int32_t id : ids) {
        shared += std::count(objects_[k].components.begin(), objects_[k].components.end(), id) > 0;
      }
      if (shared > best_shared) {
        best_shared = shared;
        best = static_cast<int>(k);
      }
    }
    MatchResult r;
    if (best < 0) return r;
    const TrueObject& k = objects_[static_cast<std::size_t>(best)];
    const double similarity = static_cast<double>(best_shared) / static_cast<double>(ids.size());
    const double completeness = static_cast<double>(best_shared) / static_cast<double>(k.components.size());
    ModelMatch m;
    m.category = k.category;
    m.model_id = k.model_id;
    if (scope == MatchScope::kFullModels) {
      m.full_model = true;
      m.entry_id = k.model_id * 100;
      m.objectness = 0.98 * similarity * similarity * completeness;
      m.T_world_model = geometry::Pose3::Identity();
      m.T_world_model.translation() = Eigen::Vector3d(k.model_id, 0.0, 0.0);
    } else {
      m.entry_id = k.model_id * 100 + static_cast<int>(ids.size());
      m.objectness = similarity == 1.0 ? part_objectness : 0.8 * similarity * similarity;
    }
    r.models.push_back(m);
    return r;
  }

  void ResetCounts() { all_calls = component_calls = pair_calls = full_calls = 0; }

  double part_objectness = 0.8;
  int all_calls = 0;
  int component_calls = 0;
  int pair_calls = 0;
  int full_calls = 0;

 private:
  std::vector<TrueObject> objects_;
  std::map<std::vector<std::int32_t>, MatchResult> table_;
};

// The paper's eq. (4) smoothness (the default is the objectness gain).
PostSegmenterOptions PaperOptions() {
  PostSegmenterOptions options;
  options.smoothness = "paper";
  options.merge_objects = false;
  return options;
}

PostSegmenterInput MakeInput(std::vector<std::int32_t> ids, std::vector<std::pair<std::int32_t, std::int32_t>> edges) {
  PostSegmenterInput input;
  for (std::int32_t id : ids) input.components.push_back({id, 1});
  input.edges = std::move(edges);
  return input;
}

const PostSegmentedObject* ObjectOf(const PostSegmentation& seg, const PostSegmenterInput& input, std::int32_t id) {
  for (std::size_t i = 0; i < input.components.size(); ++i) {
    if (input.components[i].id == id) return &seg.objects[static_cast<std::size_t>(seg.object_of_component[i])];
  }
  return nullptr;
}

// A chair pre-segmented into seat (1), back (2) and legs (3). Alone, the seat looks more like a table
// top than a chair seat; the pairs seat+back and seat+legs are strongly chair-like.
FakeMatcher ChairMatcher() {
  FakeMatcher matcher({{{1, 2, 3}, Category::kChair, 7}});
  matcher.SetAllEntries({1}, {{Category::kTable, 0.7}, {Category::kChair, 0.6}});
  matcher.SetAllEntries({2}, {{Category::kChair, 0.8}});
  matcher.SetAllEntries({3}, {{Category::kChair, 0.7}, {Category::kTable, 0.5}});
  matcher.SetAllEntries({1, 2}, {{Category::kChair, 0.9}});
  matcher.SetAllEntries({1, 3}, {{Category::kChair, 0.85}, {Category::kTable, 0.5}});
  return matcher;
}

TEST(PostSegmenterTest, ChairPartsBecomeOneCompleteChair) {
  for (bool split : {false, true}) {
    FakeMatcher matcher = ChairMatcher();
    PostSegmenterOptions options;
    options.split_instances = split;
    PostSegmenter segmenter(options, &matcher);
    const PostSegmenterInput input = MakeInput({1, 2, 3}, {{1, 2}, {1, 3}});
    const PostSegmentation seg = segmenter.Update(input);
    ASSERT_EQ(seg.objects.size(), 1u) << "split=" << split;
    const PostSegmentedObject& chair = seg.objects[0];
    EXPECT_EQ(chair.component_ids, (std::vector<std::int32_t>{1, 2, 3}));
    ASSERT_TRUE(chair.category.has_value());
    EXPECT_EQ(*chair.category, Category::kChair);
    EXPECT_DOUBLE_EQ(chair.objectness, 0.98);
    EXPECT_EQ(chair.status, ObjectStatus::kComplete);
    ASSERT_NE(chair.best_model(), nullptr);
    EXPECT_EQ(chair.best_model()->model_id, 7);
    EXPECT_DOUBLE_EQ(chair.best_model()->T_world_model.translation().x(), 7.0);
    // Energy of all-chair: data 0.4 + 0.2 + 0.3, no cut edges.
    EXPECT_NEAR(seg.energy, 0.9, 1e-12);
    EXPECT_EQ(seg.solver_status, AlphaExpansionStatus::kConverged);
    for (const auto& c : seg.category_of_component) EXPECT_EQ(c, Category::kChair);
  }
}

TEST(PostSegmenterTest, WithoutGraphCutsEveryComponentStaysAlone) {
  // The pre-segmentation baseline: no pair queries, each component labelled by its own best match.
  FakeMatcher matcher = ChairMatcher();
  PostSegmenterOptions options;
  options.graph_cuts = false;
  PostSegmenter segmenter(options, &matcher);
  const PostSegmentation seg = segmenter.Update(MakeInput({1, 2, 3}, {{1, 2}, {1, 3}}));
  ASSERT_EQ(seg.objects.size(), 3u);
  EXPECT_EQ(seg.stats.pair_queries, 0);
  EXPECT_EQ(seg.category_of_component[0], Category::kTable);  // the seat alone looks like a table top
  for (const auto& o : seg.objects) EXPECT_EQ(o.component_ids.size(), 1u);
}

TEST(PostSegmenterTest, WithoutPairEvidenceTheSeatIsLabelledTable) {
  // The smoothness term is what pulls the seat over: with weak pair objectness the seat keeps its
  // own best label, so the chair falls apart into a table top and a chair remainder.
  FakeMatcher matcher = ChairMatcher();
  matcher.SetAllEntries({1, 2}, {{Category::kChair, 0.05}});
  matcher.SetAllEntries({1, 3}, {{Category::kChair, 0.02}});
  PostSegmenterOptions options = PaperOptions();
  options.split_instances = false;
  PostSegmenter segmenter(options, &matcher);
  const PostSegmenterInput input = MakeInput({1, 2, 3}, {{1, 2}, {1, 3}});
  const PostSegmentation seg = segmenter.Update(input);
  EXPECT_EQ(seg.category_of_component[0], Category::kTable);
  EXPECT_EQ(seg.category_of_component[1], Category::kChair);
  EXPECT_EQ(seg.category_of_component[2], Category::kChair);
  // Data 0.3 + 0.2 + 0.3 plus both cut edges 0.05 + 0.02.
  EXPECT_NEAR(seg.energy, 0.87, 1e-12);
  // Back and legs are not adjacent: three objects.
  EXPECT_EQ(seg.objects.size(), 3u);
}

// Two chairs {1,2,3} and {4,5,6} touching at their seats 1 and 4.
TEST(PostSegmenterTest, TwoAdjacentChairsStayTwoWithInstanceSplitting) {
  FakeMatcher matcher({{{1, 2, 3}, Category::kChair, 7}, {{4, 5, 6}, Category::kChair, 8}});
  const PostSegmenterInput input = MakeInput({1, 2, 3, 4, 5, 6}, {{1, 2}, {1, 3}, {4, 5}, {4, 6}, {1, 4}});
  // Paper smoothness with instance splitting: one "chair" group split in two. Gain smoothness: the
  // seat-seat union is far less of a chair than either seat with its own chair (gain < 0), so the
  // edge is cut and no split is needed, with or without splitting.
  for (const auto& [smoothness, split] : {std::make_pair("paper", true), std::make_pair("gain", true),
                                          std::make_pair("gain", false)}) {
    SCOPED_TRACE(std::string(smoothness) + (split ? " split" : ""));
    PostSegmenterOptions options;
    options.smoothness = smoothness;
    options.split_instances = split;
    PostSegmenter segmenter(options, &matcher);
    const PostSegmentation seg = segmenter.Update(input);
    ASSERT_EQ(seg.objects.size(), 2u);
    EXPECT_EQ(seg.objects[0].component_ids, (std::vector<std::int32_t>{1, 2, 3}));
    EXPECT_EQ(seg.objects[1].component_ids, (std::vector<std::int32_t>{4, 5, 6}));
    for (const auto& o : seg.objects) {
      EXPECT_EQ(o.category, Category::kChair);
      EXPECT_EQ(o.status, ObjectStatus::kComplete);
    }
    EXPECT_EQ(seg.objects[0].best_model()->model_id, 7);
    EXPECT_EQ(seg.objects[1].best_model()->model_id, 8);
    EXPECT_EQ(seg.stats.splits, std::string(smoothness) == "paper" ? 1 : 0);
  }
  {
    // The paper's behaviour: one connected "chair" group, one object, which matches a single chair
    // model badly (similarity 1/2, completeness 1): 0.98 / 4.
    PostSegmenterOptions options = PaperOptions();
    options.split_instances = false;
    PostSegmenter segmenter(options, &matcher);
    const PostSegmentation seg = segmenter.Update(input);
    ASSERT_EQ(seg.objects.size(), 1u);
    EXPECT_EQ(seg.objects[0].component_ids.size(), 6u);
    EXPECT_NEAR(seg.objects[0].objectness, 0.98 / 4.0, 1e-12);
    EXPECT_EQ(seg.objects[0].status, ObjectStatus::kPartial);
  }
}

TEST(PostSegmenterTest, SplittingKeepsOneObjectWhenTheWholeIsBetter) {
  // A single chair whose parts alone and in pairs are weak: no split even when allowed.
  FakeMatcher matcher({{{1, 2, 3, 4}, Category::kChair, 3}});
  PostSegmenterOptions options;
  options.split_instances = true;
  PostSegmenter segmenter(options, &matcher);
  const PostSegmenterInput input = MakeInput({1, 2, 3, 4}, {{1, 2}, {2, 3}, {3, 4}, {1, 4}});
  const PostSegmentation seg = segmenter.Update(input);
  ASSERT_EQ(seg.objects.size(), 1u);
  EXPECT_EQ(seg.stats.splits, 0);
  EXPECT_DOUBLE_EQ(seg.objects[0].objectness, 0.98);
}

// A desk {1 top, 2 legs} with a monitor {3 screen, 4 stand} standing on the top (4 touches 1).
TEST(PostSegmenterTest, MonitorOnDeskStaysSeparate) {
  FakeMatcher matcher({{{1, 2}, Category::kDesk, 1}, {{3, 4}, Category::kMonitor, 2}});
  matcher.SetAllEntries({1}, {{Category::kDesk, 0.8}, {Category::kTable, 0.6}});
  matcher.SetAllEntries({2}, {{Category::kDesk, 0.7}, {Category::kTable, 0.65}});
  matcher.SetAllEntries({3}, {{Category::kMonitor, 0.7}});
  matcher.SetAllEntries({4}, {{Category::kMonitor, 0.5}, {Category::kLamp, 0.45}});
  matcher.SetAllEntries({1, 2}, {{Category::kDesk, 0.9}});
  matcher.SetAllEntries({3, 4}, {{Category::kMonitor, 0.9}});
  matcher.SetAllEntries({1, 4}, {{Category::kDesk, 0.2}});
  for (bool split : {false, true}) {
    PostSegmenterOptions options = PaperOptions();
    options.split_instances = split;
    PostSegmenter segmenter(options, &matcher);
    const PostSegmenterInput input = MakeInput({1, 2, 3, 4}, {{1, 2}, {3, 4}, {1, 4}});
    const PostSegmentation seg = segmenter.Update(input);
    ASSERT_EQ(seg.objects.size(), 2u) << "split=" << split;
    EXPECT_EQ(seg.objects[0].component_ids, (std::vector<std::int32_t>{1, 2}));
    EXPECT_EQ(seg.objects[0].category, Category::kDesk);
    EXPECT_EQ(seg.objects[1].component_ids, (std::vector<std::int32_t>{3, 4}));
    EXPECT_EQ(seg.objects[1].category, Category::kMonitor);
    // Data 0.2 + 0.3 + 0.3 + 0.5, and the stand-top edge is cut (0.2).
    EXPECT_NEAR(seg.energy, 1.5, 1e-12);
    EXPECT_EQ(ObjectOf(seg, input, 4), &seg.objects[1]);
  }
}

TEST(PostSegmenterTest, GainSmoothnessKeepsTheMonitorOffTheDesk) {
  // Full models: desk {1, 2}, monitor {3, 4}. Each part alone is half its model (F = 0.49), each true
  // pair the whole model (0.98, gain +0.49); stand + top is half a desk with half of it missing
  // (0.98 / 8, gain < 0): that edge is cut whatever the labels.
  FakeMatcher matcher({{{1, 2}, Category::kDesk, 1}, {{3, 4}, Category::kMonitor, 2}});
  matcher.SetAllEntries({4}, {{Category::kDesk, 0.6}, {Category::kMonitor, 0.5}});  // the stand looks like a desk leg
  const PostSegmenterInput input = MakeInput({1, 2, 3, 4}, {{1, 2}, {3, 4}, {1, 4}});
  for (bool split : {false, true}) {
    PostSegmenterOptions options;
    options.split_instances = split;
    const PostSegmentation seg = PostSegmenter(options, &matcher).Update(input);
    ASSERT_EQ(seg.objects.size(), 2u) << "split=" << split;
    EXPECT_EQ(seg.objects[0].component_ids, (std::vector<std::int32_t>{1, 2}));
    EXPECT_EQ(seg.objects[0].category, Category::kDesk);
    EXPECT_EQ(seg.objects[1].component_ids, (std::vector<std::int32_t>{3, 4}));
    EXPECT_EQ(seg.objects[1].category, Category::kMonitor);
    // Weights lambda * gain: 0.49 on both true pairs, 0 on the cut one. The stand gives up its desk
    // preference (cost 0.4 vs 0.5) to follow the screen rather than pay 0.49. Energy: the data costs
    // (parts alone match at the fake's part_objectness 0.8) and no cut edge with a weight.
    EXPECT_NEAR(seg.energy, 0.2 + 0.2 + 0.2 + 0.5, 1e-12);
  }
  // The paper's weights with a strong (all-entries) stand + top pair: the stand is cheaper as desk
  // (0.4 + cut 0.8 to the screen) than as monitor (0.5 + cut 0.9 to the top) and joins the desk.
  matcher.SetAllEntries({1, 4}, {{Category::kDesk, 0.9}});
  PostSegmenterOptions paper = PaperOptions();
  paper.split_instances = false;
  const PostSegmentation merged = PostSegmenter(paper, &matcher).Update(input);
  EXPECT_EQ(ObjectOf(merged, input, 4), ObjectOf(merged, input, 1));
  EXPECT_NE(ObjectOf(merged, input, 4), ObjectOf(merged, input, 3));
}

// A lamp in three pieces (shade 1, stem 2, base 3) whose pieces alone look like other things, on a
// night stand {4, 5}. Each pairwise union of lamp pieces is more of the lamp than its parts, but the
// graph cut keeps the stem a toilet and the base a radio (their own matches are strong and the gains
// small). Merging adjacent objects while the union beats their point-weighted mean objectness joins
// the lamp and leaves the night stand alone: lamp + night stand is 3/5 of a lamp (F = 0.35).
TEST(PostSegmenterTest, MergingAdjacentObjectsJoinsAPieceMealLampButNotItsNightStand) {
  FakeMatcher matcher({{{1, 2, 3}, Category::kLamp, 1}, {{4, 5}, Category::kNightStand, 2}});
  matcher.SetAllEntries({1}, {{Category::kLamp, 0.8}});
  matcher.SetAllEntries({2}, {{Category::kToilet, 0.9}});
  matcher.SetAllEntries({3}, {{Category::kRadio, 0.9}});
  PostSegmenterInput input = MakeInput({1, 2, 3, 4, 5}, {{1, 2}, {2, 3}, {3, 4}, {4, 5}});
  const std::size_t points[] = {500, 100, 200, 1000, 1000};
  for (std::size_t i = 0; i < 5; ++i) input.components[i].num_points = points[i];
  PostSegmenterOptions options;
  options.merge_objects = false;
  const PostSegmentation plain = PostSegmenter(options, &matcher).Update(input);
  EXPECT_EQ(plain.objects.size(), 4u);  // shade, stem, base apart; the night stand whole
  EXPECT_EQ(plain.stats.object_merges, 0);
  options.merge_objects = true;
  options.object_merge_min_gain = 0.0;
  const PostSegmentation merged = PostSegmenter(options, &matcher).Update(input);
  ASSERT_EQ(merged.objects.size(), 2u);
  EXPECT_EQ(merged.objects[0].component_ids, (std::vector<std::int32_t>{1, 2, 3}));
  EXPECT_EQ(merged.objects[0].category, Category::kLamp);  // the label of its largest piece
  EXPECT_NEAR(merged.objects[0].objectness, 0.98, 1e-12);
  EXPECT_EQ(merged.objects[1].component_ids, (std::vector<std::int32_t>{4, 5}));
  EXPECT_EQ(merged.stats.object_merges, 2);
  // A minimum gain above what the pieces offer (0.33 for the first merge) keeps them apart.
  options.object_merge_min_gain = 0.5;
  EXPECT_EQ(PostSegmenter(options, &matcher).Update(input).objects.size(), 4u);
}

// A bed fully seen (components 1-4, F = 0.98) beside a fifth of a wardrobe (component 5, the rest of
// it unseen: F = 0.98 / 5), with as many points each. Their union is 4/5 of the bed (F = 0.98 *
// 0.8^2 = 0.63): above the point-weighted mean of the two (0.59), so the mean alone would merge
// them, but the bed's own points are explained worse by it than by the bed alone.
TEST(PostSegmenterTest, MergingKeepsAWellExplainedObjectOffABadlyExplainedNeighbour) {
  FakeMatcher matcher({{{1, 2, 3, 4}, Category::kBed, 1}, {{5, 6, 7, 8, 9}, Category::kShelves, 2}});
  PostSegmenterInput input = MakeInput({1, 2, 3, 4, 5}, {{1, 2}, {2, 3}, {3, 4}, {4, 5}});
  const std::size_t points[] = {250, 250, 250, 250, 1000};
  for (std::size_t i = 0; i < 5; ++i) input.components[i].num_points = points[i];
  PostSegmenterOptions options;
  options.object_merge_min_gain = 0.0;
  options.object_merge_keep_larger_fit = false;
  const PostSegmentation mean_only = PostSegmenter(options, &matcher).Update(input);
  ASSERT_EQ(mean_only.objects.size(), 1u) << "the weighted mean alone merges them";
  options.object_merge_keep_larger_fit = true;
  const PostSegmentation kept = PostSegmenter(options, &matcher).Update(input);
  ASSERT_EQ(kept.objects.size(), 2u);
  EXPECT_EQ(kept.objects[0].component_ids, (std::vector<std::int32_t>{1, 2, 3, 4}));
  EXPECT_EQ(kept.objects[0].category, Category::kBed);
  EXPECT_EQ(kept.objects[1].component_ids, (std::vector<std::int32_t>{5}));
  EXPECT_EQ(kept.stats.object_merges, 0);
}

TEST(PostSegmenterTest, NoiseAndCompleteThresholds) {
  // Object A {1,2} fully seen (0.98: complete); object B {3,4,5} seen as one of three parts
  // (0.98/3: partial); component 9 matches nothing, neither alone nor with its neighbour 2 (none
  // label, O = 0: noise).
  FakeMatcher matcher({{{1, 2}, Category::kSofa, 1}, {{3, 4, 5}, Category::kBed, 2}});
  matcher.SetAllEntries({9}, {});
  matcher.SetAllEntries({2, 9}, {});
  PostSegmenter segmenter(PostSegmenterOptions{}, &matcher);
  const PostSegmenterInput input = MakeInput({1, 2, 3, 9}, {{1, 2}, {2, 9}});
  const PostSegmentation seg = segmenter.Update(input);
  ASSERT_EQ(seg.objects.size(), 3u);
  const PostSegmentedObject* sofa = ObjectOf(seg, input, 1);
  const PostSegmentedObject* bed = ObjectOf(seg, input, 3);
  const PostSegmentedObject* junk = ObjectOf(seg, input, 9);
  EXPECT_EQ(sofa->status, ObjectStatus::kComplete);
  EXPECT_EQ(bed->status, ObjectStatus::kPartial);
  EXPECT_NEAR(bed->objectness, 0.98 / 3.0, 1e-12);
  EXPECT_EQ(junk->status, ObjectStatus::kNoise);
  EXPECT_FALSE(junk->category.has_value());
  EXPECT_EQ(junk->best_model(), nullptr);

  // Thresholds are the options: raise "complete" above 0.98 and lower "noise" to 0 (nothing is below
  // 0), and every object is partial.
  PostSegmenterOptions options;
  options.complete_objectness = 0.99;
  options.noise_objectness = 0.0;
  PostSegmenter strict(options, &matcher);
  const PostSegmentation seg2 = strict.Update(input);
  for (const auto& o : seg2.objects) EXPECT_EQ(o.status, ObjectStatus::kPartial);
}

TEST(PostSegmenterTest, NoneLabelCostDecidesUnmatchedComponents) {
  // Component 2 matches nothing and touches a chair part with a weak pair: with a cheap "none" it
  // stays apart; with "none" as expensive as an absent category (1.0) the edge pulls it to chair.
  FakeMatcher matcher({{{1}, Category::kChair, 1}});
  matcher.SetAllEntries({2}, {});
  matcher.SetAllEntries({1, 2}, {{Category::kChair, 0.3}});
  const PostSegmenterInput input = MakeInput({1, 2}, {{1, 2}});
  PostSegmenterOptions cheap = PaperOptions();
  cheap.none_label_cost = 0.5;
  const PostSegmentation a = PostSegmenter(cheap, &matcher).Update(input);
  EXPECT_EQ(a.category_of_component[1], std::nullopt);
  EXPECT_NEAR(a.energy, 0.2 + 0.5 + 0.3, 1e-12);
  PostSegmenterOptions expensive = PaperOptions();
  expensive.none_label_cost = 1.0;
  const PostSegmentation b = PostSegmenter(expensive, &matcher).Update(input);
  EXPECT_EQ(b.category_of_component[1], Category::kChair);
  EXPECT_NEAR(b.energy, 0.2 + 1.0, 1e-12);
}

// 100 components in a chain, 50 true objects of two components each.
PostSegmenterInput ChainInput(std::vector<FakeMatcher::TrueObject>* objects) {
  PostSegmenterInput input;
  for (std::int32_t id = 0; id < 100; ++id) {
    input.components.push_back({id, 1});
    if (id > 0) input.edges.emplace_back(id - 1, id);
  }
  const Category categories[] = {Category::kChair, Category::kTable, Category::kSofa, Category::kLamp};
  for (int k = 0; k < 50; ++k) objects->push_back({{2 * k, 2 * k + 1}, categories[k % 4], k});
  return input;
}

TEST(PostSegmenterTest, WarmStepQueriesOnlyWhatChanged) {
  std::vector<FakeMatcher::TrueObject> objects;
  PostSegmenterInput input = ChainInput(&objects);
  FakeMatcher matcher(objects);
  PostSegmenter segmenter(PaperOptions(), &matcher);

  const PostSegmentation cold = segmenter.Update(input);
  EXPECT_EQ(matcher.component_calls, 100);
  EXPECT_EQ(matcher.pair_calls, 99);
  EXPECT_EQ(cold.stats.component_queries, 100);
  EXPECT_EQ(cold.stats.pair_queries, 99);
  ASSERT_EQ(cold.objects.size(), 50u);
  for (std::size_t k = 0; k < 50; ++k) {
    const std::int32_t first = static_cast<std::int32_t>(2 * k);
    EXPECT_EQ(cold.objects[k].component_ids, (std::vector<std::int32_t>{first, first + 1}));
  }
  const int cold_full_calls = matcher.full_calls;

  // Nothing changed: no matcher call at all.
  matcher.ResetCounts();
  const PostSegmentation same = segmenter.Update(input);
  EXPECT_EQ(matcher.all_calls + matcher.full_calls, 0);
  EXPECT_EQ(same.stats.component_cache_hits, 100);

  // 10 components change (one in each of 10 objects): exactly those, the pairs touching them and the
  // groups containing them are recomputed.
  for (int j = 0; j < 10; ++j) input.components[static_cast<std::size_t>(10 * j)].revision = 2;
  matcher.ResetCounts();
  const PostSegmentation warm = segmenter.Update(input);
  EXPECT_EQ(matcher.component_calls, 10);
  EXPECT_EQ(warm.stats.component_queries, 10);
  EXPECT_EQ(warm.stats.component_cache_hits, 90);
  EXPECT_EQ(matcher.pair_calls, 19);  // component 0 has one neighbour, the other nine two
  EXPECT_EQ(warm.stats.pair_cache_hits, 99 - 19);
  // Per changed object at most: the object, the changed component alone, and one merge.
  EXPECT_GT(matcher.full_calls, 0);
  EXPECT_LE(matcher.full_calls, 3 * 10);
  EXPECT_LT(matcher.full_calls, cold_full_calls / 2);

  // The cached result equals a fresh computation.
  FakeMatcher fresh_matcher(objects);
  const PostSegmentation fresh = PostSegmenter(PaperOptions(), &fresh_matcher).Update(input);
  ASSERT_EQ(fresh.objects.size(), warm.objects.size());
  for (std::size_t o = 0; o < fresh.objects.size(); ++o) {
    EXPECT_EQ(fresh.objects[o].component_ids, warm.objects[o].component_ids);
    EXPECT_EQ(fresh.objects[o].category, warm.objects[o].category);
    EXPECT_EQ(fresh.objects[o].objectness, warm.objects[o].objectness);
  }
  EXPECT_EQ(fresh.energy, warm.energy);
}

TEST(PostSegmenterTest, RemovedComponentsLeaveTheCache) {
  std::vector<FakeMatcher::TrueObject> objects;
  PostSegmenterInput input = ChainInput(&objects);
  FakeMatcher matcher(objects);
  PostSegmenter segmenter(PaperOptions(), &matcher);
  segmenter.Update(input);
  // Drop component 99, then bring it back with the same revision: it must be queried again (its
  // cache entry was dropped) and give the same result as before.
  PostSegmenterInput smaller = input;
  smaller.components.pop_back();
  smaller.edges.pop_back();
  segmenter.Update(smaller);
  matcher.ResetCounts();
  const PostSegmentation back = segmenter.Update(input);
  EXPECT_EQ(matcher.component_calls, 1);
  EXPECT_EQ(matcher.pair_calls, 1);
  EXPECT_EQ(back.objects.back().component_ids, (std::vector<std::int32_t>{98, 99}));
  segmenter.ClearCache();
  matcher.ResetCounts();
  segmenter.Update(input);
  EXPECT_EQ(matcher.component_calls, 100);
}

TEST(PostSegmenterTest, GainSmoothnessWarmStepQueriesOnlyWhatChanged) {
  std::vector<FakeMatcher::TrueObject> objects;
  PostSegmenterInput input = ChainInput(&objects);
  FakeMatcher matcher(objects);
  PostSegmenterOptions options;
  options.merge_objects = false;  // its object unions are counted in the test below
  PostSegmenter segmenter(options, &matcher);
  const PostSegmentation cold = segmenter.Update(input);
  // M(c) of every component (data term), F(c) of every component and F(c u d) of every edge (the
  // gain); the objects are true pairs, already known.
  EXPECT_EQ(matcher.component_calls, 100);
  EXPECT_EQ(matcher.pair_calls, 0);
  EXPECT_EQ(matcher.full_calls, 100 + 99);
  ASSERT_EQ(cold.objects.size(), 50u);
  for (std::size_t k = 0; k < 50; ++k) {
    const std::int32_t first = static_cast<std::int32_t>(2 * k);
    EXPECT_EQ(cold.objects[k].component_ids, (std::vector<std::int32_t>{first, first + 1}));
    EXPECT_DOUBLE_EQ(cold.objects[k].objectness, 0.98);
  }
  for (int j = 0; j < 10; ++j) input.components[static_cast<std::size_t>(10 * j)].revision = 2;
  matcher.ResetCounts();
  const PostSegmentation warm = segmenter.Update(input);
  EXPECT_EQ(matcher.component_calls, 10);
  EXPECT_EQ(matcher.full_calls, 10 + 19);
  EXPECT_EQ(warm.objects.size(), 50u);
}

// Object merging asks for unions of adjacent objects; an unchanged input asks nothing the second time.
TEST(PostSegmenterTest, ObjectMergingWarmStepQueriesNothingNew) {
  std::vector<FakeMatcher::TrueObject> objects;
  PostSegmenterInput input = ChainInput(&objects);
  FakeMatcher matcher(objects);
  PostSegmenterOptions options;
  options.merge_objects = true;
  PostSegmenter segmenter(options, &matcher);
  const PostSegmentation cold = segmenter.Update(input);
  EXPECT_GT(cold.stats.group_queries, 0);
  matcher.ResetCounts();
  const PostSegmentation warm = segmenter.Update(input);
  EXPECT_EQ(warm.stats.group_queries, 0);
  EXPECT_EQ(matcher.full_calls, 0);
  EXPECT_EQ(warm.objects.size(), cold.objects.size());
}

TEST(PostSegmenterTest, EmptyInputAndBadInput) {
  FakeMatcher matcher({});
  PostSegmenter segmenter(PostSegmenterOptions{}, &matcher);
  const PostSegmentation empty = segmenter.Update(PostSegmenterInput{});
  EXPECT_TRUE(empty.objects.empty());
  EXPECT_EQ(empty.solver_status, AlphaExpansionStatus::kEmpty);
  EXPECT_THROW(segmenter.Update(MakeInput({1, 1}, {})), InputError);
  EXPECT_THROW(segmenter.Update(MakeInput({1, 2}, {{1, 3}})), InputError);
  EXPECT_THROW(segmenter.Update(MakeInput({1, 2}, {{2, 2}})), InputError);
  PostSegmenterOptions bad;
  bad.none_label_cost = 1.5;
  EXPECT_THROW(PostSegmenter(bad, &matcher), ConfigError);
  bad = PostSegmenterOptions{};
  bad.noise_objectness = 0.97;
  EXPECT_THROW(bad.Validate(), ConfigError);
}

TEST(PostSegmenterTest, InputFromComponentGraph) {
  std::vector<Component> components(3);
  components[0].label = 2;
  components[0].revision = 5;
  components[1].label = 4;
  components[1].revision = 6;
  components[1].points.assign(3, Eigen::Vector3f::Zero());
  components[2].label = 9;
  components[2].revision = 7;
  ComponentGraph graph;
  graph.Assign(std::move(components), {{4}, {2, 9}, {4}});
  const PostSegmenterInput input = PostSegmenterInput::FromGraph(graph);
  ASSERT_EQ(input.components.size(), 3u);
  EXPECT_EQ(input.components[1].id, 4);
  EXPECT_EQ(input.components[1].revision, 6u);
  EXPECT_EQ(input.components[1].num_points, 3u);
  EXPECT_EQ(input.edges, (std::vector<std::pair<std::int32_t, std::int32_t>>{{2, 4}, {4, 9}}));
}

TEST(PostSegmenterTest, OptionsListEveryField) {
  PostSegmenterOptions options;
  const config::FlatValues values = config::Dump(options);
  std::vector<std::string> keys;
  for (const auto& kv : values) keys.push_back(kv.first);
  EXPECT_EQ(keys, (std::vector<std::string>{"none_label_cost", "complete_objectness", "noise_objectness",
                                            "split_instances", "graph_cuts", "smoothness", "smoothness_scale",
                                            "merge_min_gain", "gain_reference", "merge_objects",
                                            "object_merge_min_gain", "object_merge_keep_larger_fit", "alpha_expansion.max_sweeps",
                                            "alpha_expansion.min_improvement"}));
}

}  // namespace
}  // namespace objscan::segmentation
