#pragma once
// The whole effective configuration of objscan: one section per component. The defaults live in the
// options structs (in-class); config/default.yaml mirrors them exactly (a test keeps the two equal,
// scripts/update_default_config.sh regenerates the file).
#include <string>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/io/scene_spec.h"
#include "objscan/sim/depth_camera.h"

namespace objscan::scanning {

struct SystemConfig {
  io::SceneLoadOptions scene;
  sim::SensorOptions sensor;

  template <class V>
  void Visit(V& v) {
    v("scene", scene);
    v("sensor", sensor);
  }
  void Validate() const {
    scene.Validate();
    sensor.Validate();
  }
};

// Defaults, then `config_file` (if not empty), then each `key=value` of `overrides` in order.
// Throws InputError/ConfigError naming the file or key.
SystemConfig LoadSystemConfig(const std::string& config_file, const std::vector<std::string>& overrides);

// YAML and JSON text of the effective configuration.
std::string ToYaml(const SystemConfig& config);
std::string ToJson(const SystemConfig& config, int indent = 2);

// The project's config/ folder ($OBJSCAN_CONFIG_DIR overrides the compiled-in path).
std::string ConfigDir();

}  // namespace objscan::scanning
