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

TEST(SystemConfigTest, PaperPresetSwitchesOffWhatGoesBeyondThePaper) {
  const SystemConfig paper = LoadSystemConfig(ConfigDir() + "/paper.yaml", {});
  EXPECT_TRUE(paper.report.rules.empty());
  EXPECT_EQ(paper.scanner.stall_views, 0);
  EXPECT_DOUBLE_EQ(paper.scanner.given_up_surface_share, 0.0);
  EXPECT_GE(paper.scanner.structure_residue_fraction, 1.0);
  EXPECT_FALSE(paper.scanner.coverage_views.enabled);
  EXPECT_FALSE(paper.recognition.structure_completeness);
  EXPECT_FALSE(paper.recognition.compose_unions);
  EXPECT_DOUBLE_EQ(paper.recognition.floor_contact_m, 0.0);
  EXPECT_DOUBLE_EQ(paper.recognition.support_height_tolerance_m, 0.0);
  EXPECT_EQ(paper.postsegmentation.smoothness, "paper");
  EXPECT_FALSE(paper.postsegmentation.split_instances);
  EXPECT_FALSE(paper.postsegmentation.merge_objects);
  EXPECT_EQ(paper.presegmentation.adjacency_cell_voxels, 2);
  // The paper's parameters stay as they are in the default.
  const SystemConfig ours;
  EXPECT_EQ(paper.recognition.num_similar_models, 5);
  EXPECT_DOUBLE_EQ(paper.postsegmentation.complete_objectness, 0.96);
  EXPECT_DOUBLE_EQ(paper.postsegmentation.noise_objectness, 0.05);
  EXPECT_EQ(paper.nbv.candidates.num_candidates, ours.nbv.candidates.num_candidates);
  EXPECT_EQ(config::ToJson(config::Dump(paper.sensor)), config::ToJson(config::Dump(ours.sensor)));
}

TEST(SystemConfigTest, ReportRulesAreAListOfKnownNames) {
  const SystemConfig c = LoadSystemConfig("", {"report.rules=[door_depth, drop_small]"});
  EXPECT_EQ(c.report.rules, (std::vector<std::string>{"door_depth", "drop_small"}));
  EXPECT_TRUE(LoadSystemConfig("", {"report.rules=[]"}).report.rules.empty());
  EXPECT_THROW(LoadSystemConfig("", {"report.rules=[door_depth, teleport]"}), ConfigError);
}

}  // namespace
}  // namespace objscan::scanning
