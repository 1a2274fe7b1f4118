#pragma once
// Category labels in the files other tools open: a PLY's `red green blue` from the category palette
// (world::LabelColor, the colours of the top view legend), its `label` (category id, -1 none) and
// `instance` fields, the category names in header comments, and categories.json (id -> name, colour)
// beside them. MeshLab, Open3D and CloudCompare then show the classes; scripts find their names.
#include <cstdint>
#include <string>
#include <vector>

#include "objscan/io/ply.h"

namespace objscan::io {

// One header comment per id (-1 "unrecognized" and every world::Category), in id order:
// "category <id> <name> <red> <green> <blue>".
std::vector<std::string> CategoryPlyComments();

// Adds the `label` int property (= category_id) and the category comments to `ply`, and `instance`
// unless `instance` is null (a PLY that has its own, such as coverage.ply's ground-truth instances);
// with colour_by_category also sets its colours from the palette (a PLY coloured by something else,
// such as coverage.ply, keeps its own). One value per point; throws InputError otherwise.
void AddCategoryLabels(const std::vector<std::int32_t>& category_id, const std::vector<std::int32_t>* instance,
                       bool colour_by_category, PlyData* ply);

// categories.json: {"categories": [{"id", "name", "color": [r, g, b], "structural"}...]}, id -1
// ("unrecognized") first, then every world::Category in id order.
std::string CategoriesJson();

}  // namespace objscan::io
