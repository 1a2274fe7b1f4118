// End-to-end tests of real inputs through the objscan program: a ScanNet-format scan scanned from
// start to metrics, the AWS small house through `objscan scene`, and the malformed SDF and ScanNet
// inputs, each one line on stderr and exit 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "run_command.h"
#include "scannet_fixture.h"
#include "shared_data.h"

namespace {

namespace fs = std::filesystem;
using Result = objscan::testing::CommandResult;

Result RunObjscan(const std::string& args) { return objscan::testing::RunCommand(OBJSCAN_BINARY, args); }

using objscan::testing::CountLines;

void WriteText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

TEST(RealInputsTest, ScanNetScanRunsEndToEndWithMetrics) {
  const fs::path dir = objscan::testing::ScratchPath("objscan_scannet_e2e");
  fs::create_directories(dir);
  const std::string scan = objscan::testing::WriteScanNetFixture(dir.string(), "scene0999_00");
  const Result info = RunObjscan("scene --scene " + scan + " --info");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto scene = nlohmann::json::parse(info.out);
  EXPECT_EQ(scene["objects"].size(), 6u);
  EXPECT_EQ(scene["num_furniture"], 4);  // chair, table, trash can, unannotated

  const std::string db = (dir / "small.db").string();
  const Result build = RunObjscan("db build --models procedural --variants 1 --out " + db);
  ASSERT_EQ(build.exit_code, 0) << build.err;
  const Result run = RunObjscan("run --scene " + scan + " --db " + db + " --set scanner.max_steps=6 --out " +
                                (dir / "out").string() + " --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto j = nlohmann::json::parse(objscan::testing::ReadFile(dir / "out" / "run.json"));
  ASSERT_TRUE(j.contains("metrics"));
  // Box furniture is not recognized as any database model; what is measured is that the robot saw
  // the scan's objects (the chair and the table are categories of the database: ground truth).
  EXPECT_GE(j["metrics"]["ground_truth_objects"].get<int>(), 2);
  EXPECT_GE(j["metrics"]["coverage_visible_rate"].get<double>(), 0.3);
  EXPECT_GT(j["metrics"]["views"].get<int>(), 0);
  EXPECT_GT(j["peak_rss_mb"].get<double>(), 1.0);
  EXPECT_GT(j["cpu_s"].get<double>(), 0.0);
  // The robot started and stayed on the scan's floor (inside the 4 m x 3 m room).
  for (const auto& step : j["steps"]) {
    const double x = step["pose"]["xyz"][0], y = step["pose"]["xyz"][1];
    EXPECT_GT(x, 0.0);
    EXPECT_LT(x, 4.0);
    EXPECT_GT(y, 0.0);
    EXPECT_LT(y, 3.0);
  }
  fs::remove_all(dir);
}

TEST(RealInputsTest, AwsSmallHouseLoadsThroughTheCli) {
  OBJSCAN_REQUIRE_SHARED_DATA(data);
  const std::string house = data + "/aws-small-house";
  const Result r = RunObjscan("scene --scene " + house + "/worlds/small_house.world --model-path " + house +
                              "/models --info");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["objects"].size(), 88u);  // 87 models + the ground plane's floor
  EXPECT_TRUE(j["unmapped_models"].empty());
  // The SUNCG-only map knows none of the AWS models: all `other`, all listed, and a warning.
  const Result suncg = RunObjscan("scene --scene " + house + "/worlds/small_house.world --model-path " + house +
                                  "/models --category-map categories/suncg.yaml --info");
  ASSERT_EQ(suncg.exit_code, 0) << suncg.err;
  EXPECT_EQ(nlohmann::json::parse(suncg.out)["unmapped_models"].size(), 87u);
  EXPECT_NE(suncg.err.find("87 models have no category"), std::string::npos) << suncg.err;
}

TEST(RealInputsTest, MalformedSdfAndScanNetInputsGiveOneLineAndExit2) {
  const fs::path dir = objscan::testing::ScratchPath("objscan_real_inputs_bad");
  fs::remove_all(dir);
  const auto world = [&](const std::string& name, const std::string& body) {
    WriteText(dir / name, "<?xml version='1.0'?><sdf version='1.7'><world name='w'>" + body + "</world></sdf>\n");
    return (dir / name).string();
  };
  const std::string scan = objscan::testing::WriteScanNetFixture(dir.string(), "scene0998_00");
  WriteText(fs::path(scan) / "scene0998_00_vh_clean_2.0.010000.segs.json", "{\"segIndices\": [0]}");
  WriteText(dir / "map.yaml", "rules:\n  - {name: 'a', category: throne}\n");
  const struct {
    std::string args;
    std::string must_name;
  } cases[] = {
      {"scene --scene " + world("include.world", "<model name='m'><include><uri>model://nowhere</uri></include></model>"),
       "include.world: <include> 'model://nowhere'"},
      {"scene --scene " + world("actor.world", "<actor name='walker'><skin><filename>w.dae</filename></skin></actor>"),
       "actor.world: <actor> 'walker'"},
      {"scene --scene " + world("frame.world", "<model name='m'><pose relative_to='nope'>0 0 0 0 0 0</pose></model>"),
       "frame.world"},
      {"scene --scene " + world("static.world", "<model name='m'><static>often</static></model>"),
       "static.world: model 'm': <static> 'often'"},
      {"scene --scene " + scan + " --info", "segs.json: 1 segIndices"},
      {"scene --scene procedural:bedroom:1 --category-map " + (dir / "map.yaml").string(), ""},
      {"scene --scene " + world("ok.world", "") + " --category-map " + (dir / "map.yaml").string(),
       "map.yaml: rule 1: unknown category 'throne'"},
      {"scene --scene " + world("ok2.world", "") + " --category-map nowhere.yaml", "nowhere.yaml"},
  };
  for (const auto& c : cases) {
    if (c.must_name.empty()) continue;  // procedural scenes do not read the map
    const Result r = RunObjscan(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(CountLines(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.must_name), std::string::npos) << c.args << "\n" << r.err;
  }
  fs::remove_all(dir);
}

}  // namespace
