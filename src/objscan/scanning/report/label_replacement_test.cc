#include "objscan/scanning/report/label_replacement.h"

#include <gtest/gtest.h>

namespace objscan::scanning {
namespace {

using world::Category;

segmentation::ModelMatch Match(Category category, double objectness) {
  segmentation::ModelMatch m;
  m.category = category;
  m.full_model = true;
  m.objectness = objectness;
  return m;
}

// Monitors 0.3-0.5 m tall, 0.5-0.7 m across; shelves 1.0-2.0 m tall; windows 1.0-1.5 m tall.
recognition::CategoryExtents Extents() {
  recognition::CategoryExtents extents;
  extents.Add(Category::kMonitor, {0.3, 0.5});
  extents.Add(Category::kMonitor, {0.5, 0.7});
  extents.Add(Category::kShelves, {1.0, 0.8});
  extents.Add(Category::kShelves, {2.0, 1.2});
  extents.Add(Category::kWindow, {1.0, 1.0});
  extents.Add(Category::kWindow, {1.5, 1.6});
  extents.Add(Category::kChair, {0.8, 0.6});
  extents.Add(Category::kChair, {1.0, 0.8});
  return extents;
}

recognition::SizePlausibilityOptions Options() {
  recognition::SizePlausibilityOptions options;
  options.min_ratio = 0.8;
  options.max_ratio = 1.2;
  options.relabel_min_objectness = 0.9;
  return options;
}

const recognition::ObjectExtent kMonitorSized{0.45, 0.6};

TEST(ReplacementLabelTest, AConfidentMatchOfAnotherCategoryThatFitsTheSizeReplacesTheTakenLabel) {
  // A monitor labelled shelves: too small for shelves; its best full model is a monitor.
  segmentation::MatchResult matches;
  matches.models = {Match(Category::kShelves, 0.95), Match(Category::kMonitor, 0.93), Match(Category::kChair, 0.94)};
  const auto* r = ReplacementLabel(Category::kShelves, matches, kMonitorSized, false, Extents(), Options());
  ASSERT_NE(r, nullptr);
  // Shelves is the taken label and a chair is too tall: the monitor it is.
  EXPECT_EQ(r->category, Category::kMonitor);
  EXPECT_DOUBLE_EQ(r->objectness, 0.93);
}

TEST(ReplacementLabelTest, TheHighestObjectnessAmongQualifyingMatchesWinsWhateverTheOrder) {
  segmentation::MatchResult matches;
  matches.models = {Match(Category::kMonitor, 0.91), Match(Category::kMonitor, 0.97)};
  const auto* r = ReplacementLabel(Category::kShelves, matches, kMonitorSized, false, Extents(), Options());
  ASSERT_NE(r, nullptr);
  EXPECT_DOUBLE_EQ(r->objectness, 0.97);
}

TEST(ReplacementLabelTest, AnUnconfidentMatchLeavesTheObjectUnrecognized) {
  segmentation::MatchResult matches;
  matches.models = {Match(Category::kMonitor, 0.89)};
  EXPECT_EQ(ReplacementLabel(Category::kShelves, matches, kMonitorSized, false, Extents(), Options()), nullptr);
  recognition::SizePlausibilityOptions lower = Options();
  lower.relabel_min_objectness = 0.85;
  EXPECT_NE(ReplacementLabel(Category::kShelves, matches, kMonitorSized, false, Extents(), lower), nullptr);
}

TEST(ReplacementLabelTest, WindowsOnlyInWallOpenings) {
  // A 1.2 m flat thing whose best match is a window: outside an opening it stays unrecognized.
  const recognition::ObjectExtent extent{1.2, 1.2};
  segmentation::MatchResult matches;
  matches.models = {Match(Category::kWindow, 0.96)};
  EXPECT_EQ(ReplacementLabel(Category::kChair, matches, extent, false, Extents(), Options()), nullptr);
  const auto* r = ReplacementLabel(Category::kChair, matches, extent, true, Extents(), Options());
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->category, Category::kWindow);
}

TEST(ReplacementLabelTest, NeverACurtain) {
  // A curtain hangs over a window: the scanner's curtain check names those, so a replacement never
  // does, however confident; the next qualifying match wins instead.
  const recognition::ObjectExtent extent{1.3, 1.0};
  segmentation::MatchResult matches;
  matches.models = {Match(Category::kCurtain, 0.97)};
  EXPECT_EQ(ReplacementLabel(Category::kWindow, matches, extent, false, Extents(), Options()), nullptr);
  matches.models.push_back(Match(Category::kShelves, 0.93));
  const auto* r = ReplacementLabel(Category::kWindow, matches, extent, false, Extents(), Options());
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->category, Category::kShelves);
}

TEST(ReplacementLabelTest, NoMatchesNoReplacement) {
  EXPECT_EQ(ReplacementLabel(Category::kShelves, segmentation::MatchResult{}, kMonitorSized, false, Extents(),
                             Options()),
            nullptr);
}

TEST(ReplacementLabelTest, ObjectnessThresholdIsValidated) {
  recognition::SizePlausibilityOptions options;
  options.relabel_min_objectness = 1.5;
  EXPECT_THROW(options.Validate(), std::exception);
  options.relabel_min_objectness = 0.5;
  EXPECT_NO_THROW(options.Validate());
}

TEST(ModelLabelTest, AConfidentBestModelNamesTheObject) {
  const segmentation::ModelMatch monitor = Match(Category::kMonitor, 0.94);
  // At or above the threshold the model's category wins, also over "none".
  EXPECT_EQ(ModelLabel(Category::kShelves, &monitor, 0.93), Category::kMonitor);
  EXPECT_EQ(ModelLabel(Category::kShelves, &monitor, 0.94), Category::kMonitor);
  EXPECT_EQ(ModelLabel(std::nullopt, &monitor, 0.93), Category::kMonitor);
  // Below it, or without a model, the graph cut's label stays; 1.0 and above is the paper (off).
  EXPECT_EQ(ModelLabel(Category::kShelves, &monitor, 0.95), Category::kShelves);
  EXPECT_EQ(ModelLabel(std::nullopt, &monitor, 0.95), std::nullopt);
  EXPECT_EQ(ModelLabel(Category::kShelves, nullptr, 0.0), Category::kShelves);
  EXPECT_EQ(ModelLabel(Category::kShelves, &monitor, 1.0), Category::kShelves);
}

}  // namespace
}  // namespace objscan::scanning
