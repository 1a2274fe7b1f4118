#include "objscan/world/category.h"

namespace objscan::world {
namespace {
constexpr const char* kNames[kNumCategories] = {
    "bathtub", "bed",     "cabinet", "can",   "chair",  "curtain", "desk",    "door",
    "dresser", "lamp",    "monitor", "night_stand", "radio", "refrigerator", "shelves", "sink",
    "sofa",    "table",   "toilet",  "tv_stand", "window", "other", "floor",   "wall",  "ceiling"};

// A qualitative palette with enough distinct hues for 22 categories.
constexpr unsigned char kColors[kNumCategories][3] = {
    {31, 119, 180},  {255, 127, 14}, {44, 160, 44},   {214, 39, 40},   {148, 103, 189}, {140, 86, 75},
    {227, 119, 194}, {188, 189, 34}, {23, 190, 207},  {255, 215, 0},   {0, 0, 128},     {128, 0, 0},
    {0, 128, 128},   {170, 110, 40}, {128, 128, 0},   {0, 130, 200},   {245, 130, 48},  {145, 30, 180},
    {70, 240, 240},  {240, 50, 230}, {210, 245, 60},  {128, 150, 175}, {225, 225, 225}, {60, 60, 60},   {200, 190, 170}};
}  // namespace

const char* CategoryName(Category c) {
  const int i = static_cast<int>(c);
  return (i >= 0 && i < kNumCategories) ? kNames[i] : "unknown";
}

std::optional<Category> ParseCategory(const std::string& name) {
  for (int i = 0; i < kNumCategories; ++i) {
    if (name == kNames[i]) return static_cast<Category>(i);
  }
  return std::nullopt;
}

std::array<unsigned char, 3> CategoryColor(Category c) {
  const int i = static_cast<int>(c);
  if (i < 0 || i >= kNumCategories) return {0, 0, 0};
  return {kColors[i][0], kColors[i][1], kColors[i][2]};
}

std::array<unsigned char, 3> LabelColor(int category_id) {
  if (category_id < 0 || category_id >= kNumCategories) return kUnrecognizedColor;
  return CategoryColor(static_cast<Category>(category_id));
}

}  // namespace objscan::world
