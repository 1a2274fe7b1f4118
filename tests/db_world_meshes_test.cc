// Issue 48: a database built from a world gives back every model's mesh. `objscan db build --models
// W.world --model-path LIB` on a world whose models live in a model library (their source is
// "W.world#<object>", which nothing can load); then the world and the library are deleted and the
// database alone answers: `db info` counts a stored mesh per model within the triangle bound, and
// `db eval --queries procedural` scans every model's mesh afresh for its objectness (what stopped
// with "...#<object>: mesh file not found" before format 5).
#include <gtest/gtest.h>

#include "run_command.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace {

namespace fs = std::filesystem;

using Result = objscan::testing::CommandResult;

Result RunObjscan(const std::string& args) { return objscan::testing::RunCommand(OBJSCAN_BINARY, args); }

// An axis-aligned box [lo, hi] whose faces are grids of `step` squares (fine: many triangles), as
// OBJ lines appended to `out` after `*first_vertex - 1` earlier vertices.
void AppendGridBox(std::ofstream& out, const double lo[3], const double hi[3], double step, int* first_vertex) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    const int nu = std::max(1, static_cast<int>((hi[u] - lo[u]) / step + 0.5));
    const int nw = std::max(1, static_cast<int>((hi[w] - lo[w]) / step + 0.5));
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i <= nu; ++i) {
        for (int j = 0; j <= nw; ++j) {
          double p[3];
          p[axis] = side ? hi[axis] : lo[axis];
          p[u] = lo[u] + (hi[u] - lo[u]) * i / nu;
          p[w] = lo[w] + (hi[w] - lo[w]) * j / nw;
          out << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
        }
      }
      for (int i = 0; i < nu; ++i) {
        for (int j = 0; j < nw; ++j) {
          const int a = *first_vertex + i * (nw + 1) + j, b = a + nw + 1;
          out << "f " << a << ' ' << b << ' ' << b + 1 << '\n' << "f " << a << ' ' << b + 1 << ' ' << a + 1 << '\n';
        }
      }
      *first_vertex += (nu + 1) * (nw + 1);
    }
  }
}

// A chair (seat, back, four legs) of finely gridded boxes (~25k triangles) and a table (top, four
// legs) of plain ones.
void WriteModels(const fs::path& lib) {
  fs::create_directories(lib / "chair");
  fs::create_directories(lib / "table");
  {
    std::ofstream out(lib / "chair" / "chair.obj");
    int v = 1;
    const double seat_lo[3] = {-0.22, -0.22, 0.42}, seat_hi[3] = {0.22, 0.22, 0.47};
    const double back_lo[3] = {-0.22, 0.18, 0.47}, back_hi[3] = {0.22, 0.22, 0.9};
    AppendGridBox(out, seat_lo, seat_hi, 0.01, &v);
    AppendGridBox(out, back_lo, back_hi, 0.01, &v);
    for (double x : {-0.22, 0.18}) {
      for (double y : {-0.22, 0.18}) {
        const double lo[3] = {x, y, 0.0}, hi[3] = {x + 0.04, y + 0.04, 0.42};
        AppendGridBox(out, lo, hi, 0.01, &v);
      }
    }
  }
  {
    std::ofstream out(lib / "table" / "table.obj");
    int v = 1;
    const double top_lo[3] = {-0.6, -0.4, 0.7}, top_hi[3] = {0.6, 0.4, 0.75};
    AppendGridBox(out, top_lo, top_hi, 10.0, &v);
    for (double x : {-0.58, 0.53}) {
      for (double y : {-0.38, 0.33}) {
        const double lo[3] = {x, y, 0.0}, hi[3] = {x + 0.05, y + 0.05, 0.7};
        AppendGridBox(out, lo, hi, 10.0, &v);
      }
    }
  }
}

std::string Model(const std::string& name, const std::string& pose, const std::string& model) {
  return "<model name='" + name + "'><static>1</static><pose>" + pose +
         "</pose><link name='link'><visual name='visual'><geometry><mesh><uri>model://" + model + "/" + model +
         ".obj</uri></mesh></geometry></visual></link></model>\n";
}

void WriteWorld(const fs::path& path) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path);
  out << "<?xml version='1.0'?>\n<sdf version='1.6'><world name='default'>\n"
         "<model name='ground_plane'><static>1</static><link name='link'><visual name='visual'><geometry>"
         "<plane><normal>0 0 1</normal><size>20 20</size></plane></geometry></visual></link></model>\n"
      << Model("chair_0", "1 1 0 0 0 0.5", "chair") << Model("chair_1", "2 1 0 0 0 2.0", "chair")
      << Model("table_0", "-1 0 0 0 0 0", "table") << "</world></sdf>\n";
}

TEST(DbWorldMeshesTest, DatabaseBuiltFromAWorldGivesEveryMeshBackWithoutTheWorld) {
  const fs::path dir = objscan::testing::ScratchPath("objscan_db_world_meshes");
  WriteModels(dir / "lib");
  WriteWorld(dir / "scene" / "house.world");
  const fs::path db = dir / "house.db";
  const Result build = RunObjscan("db build --models " + (dir / "scene" / "house.world").string() + " --model-path " +
                                  (dir / "lib").string() + " --out " + db.string() + " --threads 1");
  ASSERT_EQ(build.exit_code, 0) << build.err;
  EXPECT_EQ(nlohmann::json::parse(build.out).at("models").get<int>(), 2) << build.out;  // chair and table, once each

  // Nothing of the world is left: the database alone.
  fs::remove_all(dir / "scene");
  fs::remove_all(dir / "lib");

  const Result info = RunObjscan("db info " + db.string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json meshes = nlohmann::json::parse(info.out).at("stored_meshes");
  EXPECT_EQ(meshes.at("models").get<int>(), 2) << info.out;
  // The table's 60 triangles as they are, the chair's ~25k decimated to the bound (3000).
  EXPECT_GT(meshes.at("triangles").get<int>(), 1000) << info.out;
  EXPECT_LE(meshes.at("triangles").get<int>(), 60 + 3000) << info.out;

  const Result eval = RunObjscan("db eval --db " + db.string() + " --queries procedural --queries-per-category 1 "
                                 "--threads 1 --set recognition.classifier.extra_training_databases=[]");
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  const nlohmann::json j = nlohmann::json::parse(eval.out);
  EXPECT_EQ(j.at("objectness_models").get<int>(), 2) << eval.out;  // each model's mesh scanned afresh
  // A model scanned completely again fits itself.
  EXPECT_GT(j.at("objectness_complete_mean").get<double>(), 0.5) << eval.out;
  fs::remove_all(dir);
}

}  // namespace
