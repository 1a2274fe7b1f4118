#include "objscan/recognition/component_matcher.h"

#include <gtest/gtest.h>

#include "objscan/recognition/test_database.h"

namespace objscan::recognition {
namespace {

TEST(ComponentMatcherTest, MatchesUnionsOfComponentsAndOrdersByObjectness) {
  const ModelDatabase db = BuildDatabaseFromScans(testing::ShapeModels(0.01), testing::SmallDatabaseOptions());
  const Recognizer recognizer(db, RecognitionOptions());
  // The scene: the analytic table as components (top 1, legs 2..5), moved in the world.
  ModelScan table = testing::TableScanWithComponents(0.011);
  std::vector<segmentation::Component> comps = table.components.components();
  std::vector<std::vector<std::int32_t>> neighbors;
  for (auto& c : comps) {
    for (auto& p : c.points) p += Eigen::Vector3f(2.0f, 1.0f, 0.f);
    neighbors.push_back(table.components.Neighbors(c.label));
  }
  segmentation::ComponentGraph graph;
  graph.Assign(comps, neighbors);
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

}  // namespace
}  // namespace objscan::recognition
