#include "objscan/eval/run_output.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace objscan::eval {
namespace {

// An object the graph cut left without a category ("none" label) is written with category null.
TEST(RunJsonTest, ObjectsWithAndWithoutCategory) {
  scanning::RunRecord record;
  record.terminated = scanning::Termination::kDone;
  scanning::ObjectRecord chair;
  chair.id = 3;
  chair.category = world::Category::kChair;
  chair.objectness = 0.97;
  chair.complete = true;
  scanning::ObjectRecord unknown;
  unknown.id = 7;
  unknown.objectness = 0.2;
  record.objects = {chair, unknown};
  const scanning::SystemConfig config;
  RunOutputInputs in;
  in.record = &record;
  in.config = &config;
  in.scene_spec = "procedural:bedroom:1";
  const nlohmann::json j = nlohmann::json::parse(RunJson(in));
  EXPECT_EQ(j["terminated"], "done");
  ASSERT_EQ(j["objects"].size(), 2u);
  EXPECT_EQ(j["objects"][0]["category"], "chair");
  EXPECT_TRUE(j["objects"][1]["category"].is_null());
  EXPECT_EQ(j["objects"][1]["id"], 7);
}

// The structure the robot found is written as planes: no floor is null, each wall its plane and extent.
TEST(RunJsonTest, StructureWithWallsAndNoFloor) {
  scanning::RunRecord record;
  record.terminated = scanning::Termination::kDone;
  scanning::WallRecord wall;
  wall.normal_x = 0.0;
  wall.normal_y = -1.0;
  wall.offset_m = -3.5;
  wall.span_min_m = 0.25;
  wall.span_max_m = 4.0;
  wall.z_min_m = 0.0;
  wall.z_max_m = 2.6;
  wall.area_m2 = 9.0;
  record.structure.walls = {wall};
  const scanning::SystemConfig config;
  RunOutputInputs in;
  in.record = &record;
  in.config = &config;
  nlohmann::json j = nlohmann::json::parse(RunJson(in));
  EXPECT_TRUE(j["structure"]["floor_height_m"].is_null());
  ASSERT_EQ(j["structure"]["walls"].size(), 1u);
  const auto& w = j["structure"]["walls"][0];
  EXPECT_EQ(w["normal_xy"], nlohmann::json({0.0, -1.0}));
  EXPECT_EQ(w["offset_m"], -3.5);
  EXPECT_EQ(w["span_m"], nlohmann::json({0.25, 4.0}));
  EXPECT_EQ(w["z_m"], nlohmann::json({0.0, 2.6}));
  EXPECT_EQ(w["area_m2"], 9.0);
  record.structure.floor_height_m = 0.01;
  j = nlohmann::json::parse(RunJson(in));
  EXPECT_EQ(j["structure"]["floor_height_m"], 0.01);
}

}  // namespace
}  // namespace objscan::eval
