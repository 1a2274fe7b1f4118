#pragma once
// Procedural indoor scenes and furniture: the built-in default that needs no data.
// Scene seeds and model seeds are separate streams (DeriveSeed), so a model database can be built
// from furniture that no procedural scene contains.
#include <cstdint>
#include <string>
#include <vector>

#include "objscan/geometry/mesh.h"
#include "objscan/world/category.h"
#include "objscan/world/scene.h"

namespace objscan::world::procedural {

// "bedroom", "living_room", "kitchen", "bathroom", "office".
const std::vector<std::string>& RoomCategories();

// A furniture model from parametric parts, in its own frame: metres, Z up, standing on z = 0,
// centred on the origin in XY, front facing +X. Same (category, model_seed), same mesh.
struct FurnitureModel {
  Category category = Category::kOther;
  std::string name;  // e.g. "chair_armless_pedestal_s17"
  geometry::TriangleMesh mesh;
};
// Throws InputError for categories that have no generator (can, other, floor, wall).
FurnitureModel GenerateFurniture(Category category, std::uint64_t model_seed);
// Categories GenerateFurniture supports.
const std::vector<Category>& FurnitureCategories();

// A whole room; throws InputError naming the category when it is unknown. Same seed, same scene.
Scene GenerateRoom(const std::string& room_category, std::uint64_t scene_seed);

}  // namespace objscan::world::procedural
