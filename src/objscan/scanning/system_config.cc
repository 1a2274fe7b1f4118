#include "objscan/scanning/system_config.h"

#include "objscan/io/data_paths.h"

namespace objscan::scanning {

SystemConfig LoadSystemConfig(const std::string& config_file, const std::vector<std::string>& overrides) {
  config::RawConfig raw;
  if (!config_file.empty()) raw = config::RawConfig::FromYamlFile(config_file);
  for (const auto& assignment : overrides) raw.SetFromAssignment(assignment);
  SystemConfig config;
  config::Apply(raw, &config);
  return config;
}

std::string ToYaml(const SystemConfig& config) {
  return "# objscan's default configuration: the paper's method with objscan's additions, each listed with\n"
         "# its paper value and measured effect in docs/beyond-the-paper.md (config/paper.yaml is the method\n"
         "# as published). Generated from the options structs by scripts/update_default_config.sh; a test\n"
         "# keeps it equal to the code. Copy it, edit it and pass it with --config F.yaml, or override single\n"
         "# keys with --set section.key=value.\n\n" +
         config::ToYaml(config::Dump(config));
}

std::string ToJson(const SystemConfig& config, int indent) { return config::ToJson(config::Dump(config), indent); }

std::string ConfigDir() { return io::ConfigDir(); }

}  // namespace objscan::scanning
