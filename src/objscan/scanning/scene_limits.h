#pragma once
// What `objscan run` checks before it starts: that a scene fits the configured limits
// (scene.max_extent_m, scene.max_triangles) and that the dense grids objscan builds over it at the
// configured resolutions stay within the sizes their builders accept (common/limits.h). A scene that
// does not fit fails at once with one line naming the limit and the config key, instead of running
// out of memory or failing deep inside a stage.
#include <string>

#include "objscan/scanning/system_config.h"
#include "objscan/world/scene.h"

namespace objscan::scanning {

// Throws InputError naming `spec`, the limit and the config key; returns when the scene fits.
void CheckSceneLimits(const world::Scene& scene, const SystemConfig& config, const std::string& spec);

}  // namespace objscan::scanning
