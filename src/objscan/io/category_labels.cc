#include "objscan/io/category_labels.h"

#include <nlohmann/json.hpp>

#include "objscan/common/error.h"
#include "objscan/world/category.h"

namespace objscan::io {
namespace {

// Ids -1 (unrecognized) .. kNumCategories - 1 with their names.
std::string LabelName(int id) {
  return id < 0 ? std::string("unrecognized") : std::string(world::CategoryName(static_cast<world::Category>(id)));
}

}  // namespace

std::vector<std::string> CategoryPlyComments() {
  std::vector<std::string> comments;
  comments.push_back("label: category id (-1: none), named below as: category <id> <name> <red> <green> <blue>");
  for (int id = -1; id < world::kNumCategories; ++id) {
    const auto c = world::LabelColor(id);
    comments.push_back("category " + std::to_string(id) + " " + LabelName(id) + " " + std::to_string(c[0]) + " " +
                       std::to_string(c[1]) + " " + std::to_string(c[2]));
  }
  return comments;
}

void AddCategoryLabels(const std::vector<std::int32_t>& category_id, const std::vector<std::int32_t>* instance,
                       bool colour_by_category, PlyData* ply) {
  const std::size_t n = ply->points.size();
  if (category_id.size() != n || (instance && instance->size() != n)) {
    throw InputError("category labels: " + std::to_string(category_id.size()) + " labels and " +
                     std::to_string(instance ? instance->size() : n) + " instances for " + std::to_string(n) +
                     " points");
  }
  if (colour_by_category) {
    ply->colors.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto c = world::LabelColor(category_id[i]);
      ply->colors[i] = {c[0], c[1], c[2]};
    }
  }
  ply->int_properties.emplace_back("label", category_id);
  if (instance) ply->int_properties.emplace_back("instance", *instance);
  for (std::string& comment : CategoryPlyComments()) ply->comments.push_back(std::move(comment));
}

std::string CategoriesJson() {
  nlohmann::ordered_json categories = nlohmann::ordered_json::array();
  for (int id = -1; id < world::kNumCategories; ++id) {
    const auto c = world::LabelColor(id);
    categories.push_back({{"id", id},
                          {"name", LabelName(id)},
                          {"color", {c[0], c[1], c[2]}},
                          {"structural", id >= 0 && world::IsStructural(static_cast<world::Category>(id))}});
  }
  nlohmann::ordered_json j;
  j["categories"] = categories;
  return j.dump(2) + "\n";
}

}  // namespace objscan::io
