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

// Seed streams (objscan::DeriveSeed stream ids).
//  - A room draws its layout from Rng(DeriveSeed(scene_seed, kSceneLayoutStream + room index)).
//  - The k-th piece of furniture of a room uses SceneModelSeed(room_category, scene_seed, k) =
//    DeriveSeed(DeriveSeed(scene_seed, kSceneModelStream + room index), k) with the top bit cleared.
//  - A model database uses DatabaseModelSeed(i), which always has the top bit set, so no database
//    model is ever a model of a procedural scene.
constexpr std::uint64_t kSceneLayoutStream = 0x5CE0E1A70000ull;
constexpr std::uint64_t kSceneModelStream = 0x5CE0E30D0000ull;
constexpr std::uint64_t kDatabaseModelStream = 0xDA7ABA5E0000ull;
constexpr std::uint64_t kDatabaseSeedBit = 1ull << 63;

// Model seed of the k-th furniture slot of a room (top bit clear).
std::uint64_t SceneModelSeed(const std::string& room_category, std::uint64_t scene_seed, std::uint64_t k);
// Model seed of the i-th database model (top bit set: never equal to a SceneModelSeed).
std::uint64_t DatabaseModelSeed(std::uint64_t index);

// "bedroom", "living_room", "kitchen", "bathroom", "office".
const std::vector<std::string>& RoomCategories();

// A furniture model from parametric parts, in its own frame: metres, Z up, standing on z = 0,
// centred on the origin in XY, front facing +X. Same (category, model_seed), same mesh.
struct FurnitureModel {
  Category category = Category::kOther;
  std::string name;  // e.g. "chair_armless_pedestal_s17"
  geometry::TriangleMesh mesh;
  std::uint64_t model_seed = 0;  // the seed it was generated from
};
// Throws InputError for categories that have no generator (can, other, floor, wall).
FurnitureModel GenerateFurniture(Category category, std::uint64_t model_seed);
// Categories GenerateFurniture supports.
const std::vector<Category>& FurnitureCategories();

// A whole room; throws InputError naming the category when it is unknown. Same seed, same scene.
Scene GenerateRoom(const std::string& room_category, std::uint64_t scene_seed);

}  // namespace objscan::world::procedural
