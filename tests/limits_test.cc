// Inputs too large for the configuration fail `objscan run` at once with one line naming the limit
// and its config key, exit status 2, and nothing written: a scene wider than scene.max_extent_m,
// one with more triangles than scene.max_triangles, a model database that needs more memory than
// recognition.max_database_memory_mb.
#include <gtest/gtest.h>

#include "run_command.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using Result = objscan::testing::CommandResult;

Result RunObjscan(const std::string& args) { return objscan::testing::RunCommand(OBJSCAN_BINARY, args); }

void ExpectOneLineNaming(const Result& r, const std::string& needle, const fs::path& out) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(LimitsTest, OversizedSceneOrDatabaseFailsRunEarlyNamingTheKey) {
  const fs::path dir = objscan::testing::ScratchPath("objscan_limits");
  fs::create_directories(dir);
  const fs::path out = dir / "out";
  // A 300 m long hall (two walls) with one table.
  std::ofstream(dir / "hall.yaml") << "walls:\n"
                                      "  - {min: [0, 0, 0], max: [300, 0.1, 2.5]}\n"
                                      "  - {min: [0, 5.9, 0], max: [300, 6, 2.5]}\n"
                                      "objects:\n"
                                      "  - {box: [0.8, 0.6, 0.75], category: table, pose: [2, 3, 0, 0, 0, 0]}\n";
  // Not a database, but 3 MB: the memory check needs only the file's size (about 4 x 3 MB once loaded).
  std::ofstream(dir / "big.db") << std::string(3 << 20, '\0');

  ExpectOneLineNaming(RunObjscan("run --quiet --scene " + (dir / "hall.yaml").string() + " --db " +
                                 (dir / "big.db").string() + " --out " + out.string()),
                      "scene.max_extent_m = 100 m", out);
  ExpectOneLineNaming(RunObjscan("run --quiet --scene procedural:office:1 --set scene.max_triangles=500 --db " +
                                 (dir / "big.db").string() + " --out " + out.string()),
                      "more than scene.max_triangles = 500", out);
  ExpectOneLineNaming(RunObjscan("run --quiet --scene procedural:office:1 --set recognition.max_database_memory_mb=5 "
                                 "--db " + (dir / "big.db").string() + " --out " + out.string()),
                      "needs about 12 MB of memory once loaded, more than the limit of 5 MB "
                      "(recognition.max_database_memory_mb",
                      out);
  // The same hall fits once the limit allows it: then the next check (the database) fails instead.
  const Result wider = RunObjscan("run --quiet --scene " + (dir / "hall.yaml").string() +
                                  " --set scene.max_extent_m=400 --set recognition.max_database_memory_mb=5 --db " +
                                  (dir / "big.db").string() + " --out " + out.string());
  EXPECT_EQ(wider.err.find("scene.max_extent_m"), std::string::npos) << wider.err;
  EXPECT_NE(wider.err.find("recognition.max_database_memory_mb"), std::string::npos) << wider.err;
  fs::remove_all(dir);
}

}  // namespace
