#include "objscan/scanning/system_config.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace objscan::scanning {
namespace {

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(SystemConfigTest, DefaultYamlMatchesTheCode) {
  const std::string path = ConfigDir() + "/default.yaml";
  const std::string on_disk = ReadFile(path);
  ASSERT_FALSE(on_disk.empty()) << path << " missing";
  EXPECT_EQ(on_disk, ToYaml(SystemConfig{}))
      << "config/default.yaml is out of date: run scripts/update_default_config.sh";
  // And it loads back to the defaults.
  const SystemConfig loaded = LoadSystemConfig(path, {});
  EXPECT_EQ(ToJson(loaded), ToJson(SystemConfig{}));
}

TEST(SystemConfigTest, OverridesApplyAndUnknownKeysAreRejected) {
  const SystemConfig c = LoadSystemConfig("", {"sensor.noise=false", "sensor.max_range_m=3.5"});
  EXPECT_FALSE(c.sensor.noise);
  EXPECT_DOUBLE_EQ(c.sensor.max_range_m, 3.5);
  try {
    LoadSystemConfig("", {"sensor.nosie=false"});
    FAIL() << "unknown key accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor.nosie"), std::string::npos);
  }
  EXPECT_THROW(LoadSystemConfig("/nonexistent/objscan.yaml", {}), InputError);
}

}  // namespace
}  // namespace objscan::scanning
