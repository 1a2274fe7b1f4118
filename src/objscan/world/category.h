#pragma once
// Object categories of the paper's Table 2, plus the structural classes floor, wall and ceiling.
#include <array>
#include <optional>
#include <string>

namespace objscan::world {

enum class Category : int {
  kBathtub = 0, kBed, kCabinet, kCan, kChair, kCurtain, kDesk, kDoor, kDresser, kLamp, kMonitor,
  kNightStand, kRadio, kRefrigerator, kShelves, kSink, kSofa, kTable, kToilet, kTvStand, kWindow, kOther,
  kFloor, kWall, kCeiling,
};

constexpr int kNumCategories = 25;
constexpr int kNumObjectCategories = 22;  // every category before kFloor

// Snake-case names as in the paper's Table 2 ("night_stand", "tv_stand").
const char* CategoryName(Category c);
std::optional<Category> ParseCategory(const std::string& name);
inline bool IsStructural(Category c) {
  return c == Category::kFloor || c == Category::kWall || c == Category::kCeiling;
}
inline int CategoryId(Category c) { return static_cast<int>(c); }
// Stable display colour (RGB) per category for top views and PLY export.
std::array<unsigned char, 3> CategoryColor(Category c);
// Colour of surface no category was given to ("unrecognized" in top view legends, label -1 in PLY files).
constexpr std::array<unsigned char, 3> kUnrecognizedColor = {165, 165, 165};
// The colour of a category id as written in PLY `label` fields: CategoryColor for 0..kNumCategories-1,
// kUnrecognizedColor for -1 and any other id.
std::array<unsigned char, 3> LabelColor(int category_id);

}  // namespace objscan::world
