// End-to-end tests of real inputs through the objscan program: a ScanNet-format scan scanned from
// start to metrics (with its instances annotated or inferred), the AWS small house through `objscan
// scene`, the AWS bookstore's layout of file:// URIs, a house with a closed door, and the malformed
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

// A 1 m cube as OBJ (its corner at the origin).
std::string CubeObj() {
  std::string s;
  for (int i = 0; i < 8; ++i) {
    s += "v " + std::to_string(i & 1) + " " + std::to_string((i >> 1) & 1) + " " + std::to_string((i >> 2) & 1) + "\n";
  }
  return s + "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
}

// The AWS RoboMaker bookstore's layout: PKG/worlds/bookstore.world including model://X, each
// PKG/models/X/model.sdf naming its mesh file://models/X/meshes/X_visual.obj (relative to PKG).
fs::path WriteBookstore(const fs::path& root, const std::vector<std::string>& models) {
  const fs::path pkg = root / "aws-robomaker-bookstore-world";
  std::string body;
  double x = 0.0;
  for (const std::string& name : models) {
    WriteText(pkg / "models" / name / "model.sdf",
              "<?xml version='1.0'?>\n<sdf version='1.6'>\n<model name='" + name +
                  "'>\n<link name='link'>\n<visual name='visual'>\n<geometry>\n<mesh>\n<uri>file://models/" + name +
                  "/meshes/" + name + "_visual.obj</uri>\n</mesh>\n</geometry>\n</visual>\n</link>\n</model>\n</sdf>\n");
    WriteText(pkg / "models" / name / "meshes" / (name + "_visual.obj"), CubeObj());
    body += "<model name='" + name + "_001'><include><uri>model://" + name + "</uri></include><pose frame=''>" +
            std::to_string(x) + " 0 0 0 0 0</pose></model>\n";
    x += 2.0;
  }
  WriteText(pkg / "worlds" / "bookstore.world", "<?xml version='1.0'?><sdf version='1.6'><world name='default'>" + body +
                                                   "</world></sdf>\n");
  return pkg;
}

TEST(RealInputsTest, BookstoreFileUrisLoadWithTheModelPathGivenTwice) {
  const fs::path dir = objscan::testing::ScratchPath("objscan_bookstore_e2e");
  const fs::path pkg = WriteBookstore(dir, {"aws_robomaker_retail_BookshelfA_01", "aws_robomaker_retail_DeskA_01"});
  const std::string world = (pkg / "worlds" / "bookstore.world").string();
  const Result r = RunObjscan("scene --scene " + world + " --model-path " + (dir / "nowhere").string() +
                              " --model-path " + (pkg / "models").string() + " --info");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["objects"].size(), 3u);  // the floor under them and the two models
  EXPECT_TRUE(j["missing_meshes"].empty());
  EXPECT_EQ(j["instances"], "annotated");

  // Without the model path the includes resolve nowhere: one line naming the element and the folders.
  const Result missing = RunObjscan("scene --scene " + world);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(CountLines(missing.err), 1) << missing.err;
  EXPECT_NE(missing.err.find("cannot resolve <include><uri> model://aws_robomaker_retail_BookshelfA_01; searched " +
                             (pkg / "worlds").string()),
            std::string::npos)
      << missing.err;
  // --allow-missing: no model left of two is a wrong path, one line; given twice, the floor alone.
  const Result few = RunObjscan("scene --scene " + world + " --allow-missing");
  EXPECT_EQ(few.exit_code, 2);
  EXPECT_EQ(CountLines(few.err), 1) << few.err;
  EXPECT_NE(few.err.find("only 0 of 2 models could be loaded"), std::string::npos) << few.err;
  const Result insist = RunObjscan("scene --scene " + world + " --allow-missing --allow-missing --info");
  ASSERT_EQ(insist.exit_code, 0) << insist.err;
  EXPECT_EQ(nlohmann::json::parse(insist.out)["missing_meshes"].size(), 2u);
  fs::remove_all(dir);
}

TEST(RealInputsTest, ScanNetWithoutAggregationInfersInstancesAndRunsAreScoredAgainstThem) {
  const fs::path dir = objscan::testing::ScratchPath("objscan_scannet_inferred_e2e");
  fs::create_directories(dir);
  objscan::testing::ScanNetFixtureOptions options;
  options.aggregation = false;
  options.split_chairs = true;   // each chair a seat 20 cm over its base
  options.second_chair = true;   // two chairs side by side
  const std::string scan = objscan::testing::WriteScanNetFixture(dir.string(), "scene0997_00", options);
  const Result info = RunObjscan("scene --scene " + scan + " --info");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto scene = nlohmann::json::parse(info.out);
  EXPECT_EQ(scene["instances"], "inferred");
  ASSERT_EQ(scene["load_notes"].size(), 1u);
  int chairs = 0;
  for (const auto& o : scene["objects"]) chairs += o["category"] == "chair";
  EXPECT_EQ(chairs, 2);
  EXPECT_NE(info.err.find("instances were inferred"), std::string::npos) << info.err;

  const std::string db = (dir / "small.db").string();
  ASSERT_EQ(RunObjscan("db build --models procedural --variants 1 --out " + db).exit_code, 0);
  const Result run = RunObjscan("run --scene " + scan + " --db " + db + " --set scanner.max_steps=4 --out " +
                                (dir / "out").string() + " --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto j = nlohmann::json::parse(objscan::testing::ReadFile(dir / "out" / "run.json"));
  ASSERT_TRUE(j.contains("metrics"));
  EXPECT_EQ(j["metrics"]["per_category"]["chair"]["ground_truth"], 2);
  EXPECT_EQ(j["metrics"]["per_category"]["table"]["ground_truth"], 1);
  fs::remove_all(dir);
}

TEST(RealInputsTest, ARoomBehindAClosedDoorIsListedAndDoorsOpenReachesIt) {
  const fs::path dir = objscan::testing::ScratchPath("objscan_closed_door_e2e");
  // Two 4 m x 4 m rooms (x 0-4, 4-8) joined by a 1 m doorway that a door closes; a chair in the west
  // room, a table in the east one. valve_wall_* are walls for the default category map.
  const auto box = [](const std::string& name, double x0, double y0, double z0, double x1, double y1, double z1) {
    return "<model name='" + name + "'><static>1</static><pose>" + std::to_string((x0 + x1) / 2) + " " +
           std::to_string((y0 + y1) / 2) + " " + std::to_string((z0 + z1) / 2) +
           " 0 0 0</pose><link name='l'><visual name='v'><geometry><box><size>" + std::to_string(x1 - x0) + " " +
           std::to_string(y1 - y0) + " " + std::to_string(z1 - z0) + "</size></box></geometry></visual></link></model>\n";
  };
  const std::string world =
      "<?xml version='1.0'?><sdf version='1.6'><world name='default'>"
      "<model name='ground_plane'><static>1</static><link name='l'><visual name='v'><geometry><plane><normal>0 0 1"
      "</normal><size>100 100</size></plane></geometry></visual></link></model>\n" +
      box("valve_wall_1", -0.1, -0.1, 0, 8.1, 0, 2.5) + box("valve_wall_2", -0.1, 4, 0, 8.1, 4.1, 2.5) +
      box("valve_wall_3", -0.1, 0, 0, 0, 4, 2.5) + box("valve_wall_4", 8, 0, 0, 8.1, 4, 2.5) +
      box("valve_wall_5", 3.95, 0, 0, 4.05, 1.5, 2.5) + box("valve_wall_6", 3.95, 2.5, 0, 4.05, 4, 2.5) +
      box("valve_wall_7", 3.95, 1.5, 2.1, 4.05, 2.5, 2.5) + box("door_1", 3.98, 1.5, 0, 4.02, 2.5, 2.05) +
      box("chair_1", 1.0, 1.0, 0, 1.5, 1.5, 0.9) + box("table_1", 6.5, 2.8, 0, 7.5, 3.6, 0.75) + "</world></sdf>\n";
  WriteText(dir / "house.world", world);
  const std::string db = (dir / "small.db").string();
  ASSERT_EQ(RunObjscan("db build --models procedural --variants 1 --out " + db).exit_code, 0);
  const std::string common = "run --scene " + (dir / "house.world").string() + " --db " + db +
                             " --set scanner.max_steps=3 --quiet --out ";
  const Result closed = RunObjscan(common + (dir / "closed").string());
  ASSERT_EQ(closed.exit_code, 0) << closed.err;
  EXPECT_NE(closed.err.find("1 room (") , std::string::npos) << closed.err;
  const auto j = nlohmann::json::parse(objscan::testing::ReadFile(dir / "closed" / "run.json"));
  ASSERT_EQ(j["metrics"]["unreachable_rooms"].size(), 1u) << j["metrics"]["unreachable_rooms"].dump();
  const auto& room = j["metrics"]["unreachable_rooms"][0];
  // The robot starts in the larger free area: the west room (the chair is smaller than the table).
  ASSERT_EQ(room["objects"].size(), 1u) << room.dump();
  const bool table_unreachable = room["objects"][0]["name"] == "table_1";
  EXPECT_EQ(room["objects"][0]["category"], table_unreachable ? "table" : "chair");
  EXPECT_EQ(j["metrics"]["ground_truth_objects"].get<int>() - j["metrics"]["reachable"]["ground_truth_objects"].get<int>(),
            1);
  const auto out = nlohmann::json::parse(closed.out);
  EXPECT_EQ(out["unreachable_rooms"], 1);
  // Doors open: the door is gone and every room is reachable.
  const Result open = RunObjscan(common + (dir / "open").string() + " --doors-open");
  ASSERT_EQ(open.exit_code, 0) << open.err;
  const auto o = nlohmann::json::parse(objscan::testing::ReadFile(dir / "open" / "run.json"));
  EXPECT_TRUE(o["metrics"]["unreachable_rooms"].empty());
  EXPECT_EQ(o["metrics"]["reachable"]["ground_truth_objects"], o["metrics"]["ground_truth_objects"]);
  EXPECT_TRUE(o["config"]["scene"]["doors_open"].get<bool>());
  fs::remove_all(dir);
}

TEST(RealInputsTest, ReportOfAFolderWithoutRunsSaysSoAndWritesNothing) {
  const fs::path dir = objscan::testing::ScratchPath("objscan_report_no_run");
  fs::create_directories(dir / "empty");
  for (const fs::path& target : {dir / "empty", dir / "typo"}) {
    const Result r = RunObjscan("report " + target.string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(CountLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(target.string()), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(fs::exists(target / "report"));
  }
  EXPECT_TRUE(fs::is_empty(dir / "empty"));
  fs::remove_all(dir);
}

}  // namespace
