// `objscan db build --models` from mixed sources: the built-in generator's models together with a
// user's model folder give exactly the models of both (counted from a folder of two boxes and the
// generator's one model per category); `db eval --queries` refuses to mix the unseen generator
// queries with other queries, in one line with exit status 2.
#include <gtest/gtest.h>

#include "run_command.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace {

namespace fs = std::filesystem;

using Result = objscan::testing::CommandResult;

Result RunObjscan(const std::string& args) { return objscan::testing::RunCommand(OBJSCAN_BINARY, args); }

// An axis-aligned box standing on z = 0 as a Wavefront OBJ (8 vertices, 12 triangles).
void WriteBox(const fs::path& path, double sx, double sy, double sz) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path);
  for (int i = 0; i < 8; ++i) {
    out << "v " << ((i & 1) ? sx : 0.0) << ' ' << ((i & 2) ? sy : 0.0) << ' ' << ((i & 4) ? sz : 0.0) << '\n';
  }
  const int faces[12][3] = {{1, 3, 2}, {2, 3, 4}, {5, 6, 7}, {6, 8, 7}, {1, 2, 5}, {2, 6, 5},
                            {3, 7, 4}, {4, 7, 8}, {1, 5, 3}, {3, 5, 7}, {2, 4, 6}, {4, 8, 6}};
  for (const auto& f : faces) out << "f " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
}

int ModelCount(const Result& r) { return nlohmann::json::parse(r.out).at("models").get<int>(); }

TEST(DbBuildSourcesTest, ProceduralModelsAndAModelFolderMakeOneDatabase) {
  const fs::path dir = objscan::testing::ScratchPath("objscan_db_build_sources");
  fs::remove_all(dir);
  const fs::path models = dir / "models";
  WriteBox(models / "cabinet" / "tall_box.obj", 0.6, 0.5, 1.8);
  WriteBox(models / "table" / "slab.obj", 1.4, 0.8, 0.75);

  const Result generated = RunObjscan("db build --models procedural --variants 1 --out " + (dir / "p.db").string());
  ASSERT_EQ(generated.exit_code, 0) << generated.err;
  const Result folder = RunObjscan("db build --models " + models.string() + " --out " + (dir / "f.db").string());
  ASSERT_EQ(folder.exit_code, 0) << folder.err;
  EXPECT_EQ(ModelCount(folder), 2);
  const Result both = RunObjscan("db build --models procedural " + models.string() + " --variants 1 --out " +
                                 (dir / "both.db").string());
  ASSERT_EQ(both.exit_code, 0) << both.err;
  EXPECT_EQ(ModelCount(both), ModelCount(generated) + 2);

  // The user's boxes are in it by name, under their folder's category.
  const Result info = RunObjscan("db info " + (dir / "both.db").string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json categories = nlohmann::json::parse(info.out).at("categories");
  const Result generated_info = RunObjscan("db info " + (dir / "p.db").string());
  const nlohmann::json generated_categories = nlohmann::json::parse(generated_info.out).at("categories");
  for (const char* c : {"cabinet", "table"}) {
    EXPECT_EQ(categories.at(c).at("models").get<int>(), generated_categories.at(c).at("models").get<int>() + 1) << c;
  }

  const Result mixed_queries =
      RunObjscan("db eval --db " + (dir / "both.db").string() + " --queries procedural " + models.string());
  EXPECT_EQ(mixed_queries.exit_code, 2) << mixed_queries.err;
  EXPECT_EQ(std::count(mixed_queries.err.begin(), mixed_queries.err.end(), '\n'), 1) << mixed_queries.err;
  EXPECT_NE(mixed_queries.err.find("--queries procedural"), std::string::npos) << mixed_queries.err;
  fs::remove_all(dir);
}

}  // namespace
