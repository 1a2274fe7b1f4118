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

}  // namespace
}  // namespace objscan::eval
