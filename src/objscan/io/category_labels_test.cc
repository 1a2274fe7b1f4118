#include "objscan/io/category_labels.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "objscan/io/test_util.h"
#include "objscan/world/category.h"

namespace objscan::io {
namespace {

using testing::ExpectInputError;
using testing::TempDir;

// A labelled cloud read back: colours from the palette per category (grey for -1), `label` and
// `instance` after the fields it had, every category named in the header.
TEST(CategoryLabelsTest, PlyCarriesColoursLabelsInstancesAndNames) {
  TempDir dir;
  PlyData d;
  for (int i = 0; i < 4; ++i) d.points.emplace_back(i, 0, 0);
  d.int_properties.emplace_back("object_id", std::vector<std::int32_t>{5, 5, 9, -1});
  const std::vector<std::int32_t> category{world::CategoryId(world::Category::kChair),
                                           world::CategoryId(world::Category::kChair),
                                           world::CategoryId(world::Category::kWall), -1};
  const std::vector<std::int32_t> instance{5, 5, 9, -1};
  AddCategoryLabels(category, &instance, /*colour_by_category=*/true, &d);
  WritePly(dir.File("l.ply"), d);
  const PlyData back = ReadPly(dir.File("l.ply"));
  ASSERT_EQ(back.colors.size(), 4u);
  EXPECT_EQ(back.colors[0], (std::array<std::uint8_t, 3>{148, 103, 189}));  // chair in the palette
  EXPECT_EQ(back.colors[1], back.colors[0]);
  EXPECT_EQ(back.colors[2], (std::array<std::uint8_t, 3>{60, 60, 60}));     // wall
  EXPECT_EQ(back.colors[3], (std::array<std::uint8_t, 3>{165, 165, 165}));  // unrecognized
  ASSERT_EQ(back.int_properties.size(), 3u);
  EXPECT_EQ(back.int_properties[0].first, "object_id");
  EXPECT_EQ(back.int_properties[1].first, "label");
  EXPECT_EQ(back.int_properties[1].second, category);
  EXPECT_EQ(back.int_properties[2].first, "instance");
  EXPECT_EQ(back.int_properties[2].second, instance);
  // The writer's line, the legend line, then -1 and the 25 categories.
  ASSERT_EQ(back.comments.size(), 2u + 1u + world::kNumCategories);
  EXPECT_EQ(back.comments[2], "category -1 unrecognized 165 165 165");
  EXPECT_EQ(back.comments[3], "category 0 bathtub 31 119 180");
  EXPECT_EQ(back.comments[3 + world::CategoryId(world::Category::kChair)], "category 4 chair 148 103 189");
  EXPECT_EQ(back.comments.back(), "category 24 ceiling 200 190 170");
}

// coverage.ply keeps its own colours and instance field: only `label` is added.
TEST(CategoryLabelsTest, KeepsOwnColoursAndInstance) {
  PlyData d;
  d.points.emplace_back(0, 0, 0);
  d.colors.push_back({1, 2, 3});
  d.int_properties.emplace_back("instance", std::vector<std::int32_t>{12});
  AddCategoryLabels({world::CategoryId(world::Category::kBed)}, nullptr, /*colour_by_category=*/false, &d);
  EXPECT_EQ(d.colors[0], (std::array<std::uint8_t, 3>{1, 2, 3}));
  ASSERT_EQ(d.int_properties.size(), 2u);
  EXPECT_EQ(d.int_properties[1].first, "label");
  EXPECT_EQ(d.int_properties[1].second, std::vector<std::int32_t>{1});
  ExpectInputError([&] { AddCategoryLabels({1, 2}, nullptr, true, &d); }, "2 labels");
}

// categories.json lists -1 and every category with the palette colour the PLY comments give.
TEST(CategoryLabelsTest, CategoriesJsonMatchesThePalette) {
  const nlohmann::json j = nlohmann::json::parse(CategoriesJson());
  const auto& c = j.at("categories");
  ASSERT_EQ(c.size(), 1u + world::kNumCategories);
  EXPECT_EQ(c[0]["id"], -1);
  EXPECT_EQ(c[0]["name"], "unrecognized");
  EXPECT_EQ(c[0]["color"], nlohmann::json({165, 165, 165}));
  for (int id = 0; id < world::kNumCategories; ++id) {
    const auto& e = c[id + 1];
    const auto cat = static_cast<world::Category>(id);
    EXPECT_EQ(e["id"], id);
    EXPECT_EQ(e["name"], world::CategoryName(cat));
    const auto rgb = world::CategoryColor(cat);
    EXPECT_EQ(e["color"], nlohmann::json({rgb[0], rgb[1], rgb[2]}));
    EXPECT_EQ(e["structural"], world::IsStructural(cat)) << id;
  }
  EXPECT_EQ(c[1 + world::CategoryId(world::Category::kNightStand)]["name"], "night_stand");
}

}  // namespace
}  // namespace objscan::io
