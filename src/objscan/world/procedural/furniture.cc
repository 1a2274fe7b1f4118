#include <string>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"
#include "objscan/world/procedural/furniture_generators.h"
#include "objscan/world/procedural/procedural.h"

namespace objscan::world::procedural {

const std::vector<Category>& FurnitureCategories() {
  static const std::vector<Category> kCategories = {
      Category::kBathtub,  Category::kBed,         Category::kCabinet, Category::kChair,   Category::kCurtain,
      Category::kDesk,     Category::kDoor,        Category::kDresser, Category::kLamp,    Category::kMonitor,
      Category::kNightStand, Category::kRadio,     Category::kRefrigerator, Category::kShelves,
      Category::kSink,     Category::kSofa,        Category::kTable,   Category::kToilet,  Category::kTvStand,
      Category::kWindow};
  return kCategories;
}

std::uint64_t DatabaseModelSeed(std::uint64_t index) {
  return DeriveSeed(index, kDatabaseModelStream) | kDatabaseSeedBit;
}

namespace internal {
bool BuildFurnitureFromSeed(Category category, std::uint64_t model_seed, PartBuilder* parts, std::string* variant) {
  // Each category draws from its own stream so one seed gives unrelated models per category.
  Rng rng(DeriveSeed(model_seed, 0xF0E0000ull + static_cast<std::uint64_t>(CategoryId(category))));
  return BuildFurniture(category, rng, *parts, variant);
}
}  // namespace internal

FurnitureModel GenerateFurniture(Category category, std::uint64_t model_seed) {
  PartBuilder parts;
  std::string variant;
  if (!internal::BuildFurnitureFromSeed(category, model_seed, &parts, &variant)) {
    throw InputError(std::string("procedural furniture: no generator for category '") + CategoryName(category) +
                     "'");
  }
  FurnitureModel model;
  model.category = category;
  model.name = std::string(CategoryName(category)) + "_" + variant + "_s" + std::to_string(model_seed);
  model.mesh = parts.Finish();
  model.model_seed = model_seed;
  return model;
}

}  // namespace objscan::world::procedural
