#include "objscan/recognition/component_matcher.h"

#include <gtest/gtest.h>

#include <string>

#include "objscan/recognition/shape_database_suite.h"

namespace objscan::recognition {
namespace {

// Both ways of describing a union: composed from the cached parts (default) and from its points.
class ComponentMatcherTest : public testing::ShapeDatabaseSuite<::testing::TestWithParam<bool>> {
 protected:
  static RecognitionOptions Options() {
    RecognitionOptions options;
    options.compose_unions = GetParam();
    return options;
  }
};

// The analytic table as a component graph (top 1, legs 2..5), moved by `offset` in the world, every
// component at `revision`.
segmentation::ComponentGraph TableGraph(const Eigen::Vector3f& offset, std::uint64_t revision = 0) {
  ModelScan table = testing::TableScanWithComponents(0.011);
  std::vector<segmentation::Component> comps = table.components.components();
  std::vector<std::vector<std::int32_t>> neighbors;
  for (auto& c : comps) {
    for (auto& p : c.points) p += offset;
    c.revision = revision;
    neighbors.push_back(table.components.Neighbors(c.label));
  }
  segmentation::ComponentGraph graph;
  graph.Assign(comps, neighbors);
  return graph;
}

TEST_P(ComponentMatcherTest, MatchesUnionsOfComponentsAndOrdersByObjectness) {
  const ModelDatabase& db = *db_;
  const Recognizer recognizer(db, Options());
  const segmentation::ComponentGraph graph = TableGraph(Eigen::Vector3f(2.0f, 1.0f, 0.f));
  RecognizerComponentMatcher matcher(recognizer, 1);
  matcher.SetComponents(&graph);

  const auto whole = matcher.Match({1, 2, 3, 4, 5}, segmentation::MatchScope::kFullModels);
  ASSERT_FALSE(whole.models.empty());
  EXPECT_EQ(whole.models[0].category, world::Category::kTable);
  EXPECT_TRUE(whole.models[0].full_model);
  EXPECT_GT(whole.BestObjectness(), 0.9);
  EXPECT_NEAR(whole.models[0].T_world_model.translation().x(), 2.0, 0.05);
  for (std::size_t i = 1; i < whole.models.size(); ++i)
    EXPECT_GE(whole.models[i - 1].objectness, whole.models[i].objectness);

  const auto leg = matcher.Match({3}, segmentation::MatchScope::kAllEntries);
  ASSERT_FALSE(leg.models.empty());
  EXPECT_EQ(leg.models[0].category, world::Category::kTable);
  EXPECT_FALSE(leg.models[0].full_model);

  const auto batch = matcher.MatchBatch({{1, 2, 3, 4, 5}, {3}}, segmentation::MatchScope::kAllEntries);
  ASSERT_EQ(batch.size(), 2u);
  EXPECT_EQ(batch[1].models.size(), leg.models.size());
  EXPECT_TRUE(matcher.Match({99}, segmentation::MatchScope::kAllEntries).models.empty());
}

// Context may name the category (an object in a wall opening is a window): the best model of that
// category is found by aligning every one of its full models, whether retrieval ranked it or not.
TEST_P(ComponentMatcherTest, BestOfACategoryAlignsEveryModelOfIt) {
  const Recognizer recognizer(*db_, Options());
  const segmentation::ComponentGraph graph = TableGraph(Eigen::Vector3f(2.0f, 1.0f, 0.f));
  RecognizerComponentMatcher matcher(recognizer, 1);
  matcher.SetComponents(&graph);
  const auto whole = matcher.Match({1, 2, 3, 4, 5}, segmentation::MatchScope::kFullModels);
  ASSERT_FALSE(whole.models.empty());

  const auto table = matcher.BestOfCategory({1, 2, 3, 4, 5}, world::Category::kTable);
  ASSERT_TRUE(table.has_value());
  EXPECT_EQ(table->category, world::Category::kTable);
  EXPECT_TRUE(table->full_model);
  EXPECT_EQ(table->model_id, whole.models[0].model_id);
  EXPECT_NEAR(table->objectness, whole.BestObjectness(), 0.02);
  EXPECT_NEAR(table->T_world_model.translation().x(), 2.0, 0.05);

  // The table as a sofa: the sofa model, placed, and a worse fit than the table's.
  const auto sofa = matcher.BestOfCategory({1, 2, 3, 4, 5}, world::Category::kSofa);
  ASSERT_TRUE(sofa.has_value());
  EXPECT_EQ(sofa->category, world::Category::kSofa);
  EXPECT_EQ(recognizer.database().models()[sofa->model_id].category, world::Category::kSofa);
  EXPECT_LT(sofa->objectness, table->objectness);

  // No window in the database, and no points for an unknown component.
  EXPECT_FALSE(matcher.BestOfCategory({1, 2, 3, 4, 5}, world::Category::kWindow).has_value());
  EXPECT_FALSE(matcher.BestOfCategory({99}, world::Category::kTable).has_value());
}

// A component whose points changed (new revision) is described anew: the cached description of the
// old points must not answer for it.
TEST_P(ComponentMatcherTest, ChangedComponentIsDescribedAnew) {
  const Recognizer recognizer(*db_, Options());
  const segmentation::ComponentGraph graph = TableGraph(Eigen::Vector3f::Zero(), 1);
  RecognizerComponentMatcher matcher(recognizer, 1);
  matcher.SetComponents(&graph);
  const auto before = matcher.Match({1, 2, 3, 4, 5}, segmentation::MatchScope::kFullModels);
  ASSERT_FALSE(before.models.empty());

  // The whole table moves 3 m along x; every component gets a new revision.
  const segmentation::ComponentGraph moved = TableGraph(Eigen::Vector3f(3.0f, 0.f, 0.f), 2);
  matcher.SetComponents(&moved);
  const auto after = matcher.MatchBatch({{1, 2, 3, 4, 5}, {1}}, segmentation::MatchScope::kFullModels);
  ASSERT_FALSE(after[0].models.empty());
  EXPECT_EQ(after[0].models[0].category, world::Category::kTable);
  EXPECT_NEAR(after[0].models[0].T_world_model.translation().x() - before.models[0].T_world_model.translation().x(),
              3.0, 0.05);
}

INSTANTIATE_TEST_SUITE_P(UnionDescription, ComponentMatcherTest, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? std::string("Composed") : std::string("FromPoints");
                         });

}  // namespace
}  // namespace objscan::recognition
