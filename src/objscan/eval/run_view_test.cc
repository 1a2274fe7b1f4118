#include "objscan/eval/run_view.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "objscan/io/ply.h"
#include "objscan/world/category.h"

namespace objscan::eval {
namespace {

namespace fs = std::filesystem;
using world::Category;
using world::CategoryId;

class RunViewTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("objscan_run_view_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // Stand-ins for three.js: the page inlines whatever the files hold.
    Write("three.js", "var THREE = {stub: 'three'};");
    Write("orbit.js", "THREE.OrbitControls = 'orbit stub';");
    options_.three_js_path = (dir_ / "three.js").string();
    options_.orbit_controls_path = (dir_ / "orbit.js").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  void Write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }

  // A run of two steps: view 0 at (0, 0, 1) looking along +x, view 1 at (5, 0, 1) looking back along -x.
  void WriteRun() {
    nlohmann::json sensor{{"width_px", 640}, {"height_px", 480}, {"fx_px", 525.0}, {"fy_px", 525.0}, {"cx_px", 319.5},
                          {"cy_px", 239.5},  {"min_range_m", 0.5}, {"max_range_m", 4.0}};
    nlohmann::json candidate_pose{{"xyz", {1.0, 1.0, 1.2}}, {"yaw_deg", 90.0}, {"pitch_deg", -10.0}};
    nlohmann::json run{
        {"scene", "room</script>x"},
        {"seed", 4},
        {"terminated", "done"},
        {"config", {{"sensor", sensor}}},
        {"steps",
         {{{"index", 0}, {"action", "nbo"}, {"ooi", 9}},
          {{"index", 1},
           {"action", "nbo"},
           {"ooi", 7},
           {"nbv_candidates",
            {{{"pose", candidate_pose}, {"validity", "valid"}, {"gain", 2.5}},
             {{"pose", candidate_pose}, {"validity", "too_close"}, {"gain", 0.0}}}}}}},
        {"objects", nlohmann::json::array()}};
    Write("run.json", run.dump());
    Write("trajectory.csv",
          "step,time_s,base_x_m,base_y_m,base_theta_deg,camera_x_m,camera_y_m,camera_z_m,camera_yaw_deg,camera_pitch_deg,view\n"
          "0,1.0,0,0,0,0,0,1,0,0,1\n"
          "1,2.0,2.5,0.5,0,2.5,0.5,1,0,0,0\n"
          "1,3.0,5,0,180,5,0,1,180,0,1\n");
    // A (2, 0, 1) chair: seen by view 0. C (3, 0, 1) table: behind A from view 0, seen by view 1.
    // D (2, 0, 3.5) lamp: above both frusta, shown at the end. E ceiling: left out.
    io::PlyData scene;
    scene.points = {{3, 0, 1}, {2, 0, 3.5f}, {2, 0, 1}, {1, 0, 2.6f}};
    scene.int_properties.emplace_back(
        "label", std::vector<std::int32_t>{CategoryId(Category::kTable), CategoryId(Category::kLamp),
                                           CategoryId(Category::kChair), CategoryId(Category::kCeiling)});
    io::WritePly((dir_ / "scene.ply").string(), scene);
    // Objects 7 and 9 (the objects of interest of steps 1 and 0) and 11 (never one): two triangles each.
    io::PlyData models;
    std::vector<std::int32_t> labels, instances;
    for (int object : {7, 9, 11}) {
      const int first = static_cast<int>(models.points.size());
      for (int k = 0; k < 4; ++k) {
        models.points.emplace_back(object + 0.1f * k, 0.0f, 0.1f * (k % 2));
        labels.push_back(object == 7 ? 1 : 15);
        instances.push_back(object);
      }
      models.triangles.emplace_back(first, first + 1, first + 2);
      models.triangles.emplace_back(first + 1, first + 2, first + 3);
    }
    models.int_properties.emplace_back("label", labels);
    models.int_properties.emplace_back("instance", instances);
    io::WritePly((dir_ / "models.ply").string(), models);
  }

  static nlohmann::json Data(const std::string& html) {
    const std::string open = "<script id=\"objscan-data\" type=\"application/json\">";
    const std::size_t begin = html.find(open);
    EXPECT_NE(begin, std::string::npos);
    const std::size_t end = html.find("</script>", begin);
    return nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
  }

  fs::path dir_;
  RunViewOptions options_;
};

TEST_F(RunViewTest, PointsAppearAtTheFirstViewThatSawThemModelsAtTheirObjectsStep) {
  WriteRun();
  RunViewSummary summary;
  const std::string html = RunViewHtml(dir_.string(), options_, &summary);
  EXPECT_NE(html.find("var THREE = {stub: 'three'};"), std::string::npos);
  EXPECT_NE(html.find("THREE.OrbitControls = 'orbit stub';"), std::string::npos);
  EXPECT_EQ(html.find("/*OBJSCAN_"), std::string::npos);  // every marker filled
  EXPECT_EQ(html.find("room</script>"), std::string::npos);  // the scene name cannot end the element
  const nlohmann::json data = Data(html);
  EXPECT_NE(data["title"].get<std::string>().find("room</script>x, seed 4: done, 2 views"), std::string::npos);

  // A (view 0), then C (hidden behind A from view 0, seen by view 1) and D (in no frustum: the end).
  EXPECT_EQ(data["points"]["count"], 3);
  EXPECT_EQ(data["points"]["after_view"], nlohmann::json({1, 3}));
  EXPECT_EQ(summary.points, 3);
  EXPECT_EQ(summary.scene_points, 4);
  EXPECT_EQ(summary.views, 2);
  EXPECT_EQ(summary.steps, 2);
  EXPECT_EQ(summary.candidates, 2);
  // Labels in that order, as little-endian int32 in base64: chair (4), table (17), lamp (9).
  EXPECT_EQ(data["points"]["label"], "BAAAABEAAAAJAAAA");

  ASSERT_EQ(data["views"].size(), 2u);
  EXPECT_EQ(data["views"][1], nlohmann::json({5.0, 0.0, 1.0, 180.0, 0.0, 1}));
  EXPECT_EQ(data["path"].size(), 3u);
  EXPECT_EQ(data["steps"][1]["candidates"][0], nlohmann::json({1.0, 1.0, 1.2, 90.0, -10.0, 2.5, 1}));
  EXPECT_EQ(data["steps"][1]["candidates"][1][6], 0);
  EXPECT_NEAR(data["sensor"]["hfov_deg"].get<double>(), 62.72, 0.01);

  ASSERT_EQ(data["models"].size(), 3u);
  for (const auto& m : data["models"]) {
    const int object = m["object"];
    EXPECT_EQ(m["step"], object == 9 ? 0 : 1) << object;  // its last step as object of interest, else the end
    EXPECT_EQ(m["label"], object == 7 ? 1 : 15) << object;
  }
  EXPECT_EQ(summary.models, 3);
}

TEST_F(RunViewTest, BadInputNamesTheFile) {
  const auto expect_error = [&](const std::string& needle) {
    try {
      RunViewHtml(dir_.string(), options_);
      ADD_FAILURE() << "expected an error naming " << needle;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_error("run.json");
  WriteRun();
  Write("trajectory.csv",
        "step,time_s,base_x_m,base_y_m,base_theta_deg,camera_x_m,camera_y_m,camera_z_m,camera_yaw_deg,camera_pitch_deg,view\n"
        "0,1.0,0,zero,0,0,0,1,0,0,1\n");
  expect_error("trajectory.csv: line 2");
  WriteRun();
  options_.three_js_path = (dir_ / "missing_three.js").string();
  expect_error("missing_three.js");
  options_.max_points = 0;
  expect_error("max_points");
}

}  // namespace
}  // namespace objscan::eval
