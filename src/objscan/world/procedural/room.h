#pragma once
// GenerateRoom with explicit options (procedural.h has the default-options version).
#include <cstdint>
#include <string>

#include "objscan/world/procedural/room_options.h"
#include "objscan/world/scene.h"

namespace objscan::world::procedural {

Scene GenerateRoom(const std::string& room_category, std::uint64_t scene_seed, const RoomOptions& options);

}  // namespace objscan::world::procedural
