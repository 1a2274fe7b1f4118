// End-to-end tests of `objscan bench` and `objscan report` that need no scanning: bad input, and a
// suite whose runs are all finished already (resume skips every run and only rebuilds the report).
#include <gtest/gtest.h>

#include "run_command.h"
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace {

namespace fs = std::filesystem;

using Result = objscan::testing::CommandResult;

Result RunObjscan(const std::string& args) { return objscan::testing::RunCommand(OBJSCAN_BINARY, args); }

fs::path TempDir(const std::string& name) {
  const fs::path d = objscan::testing::ScratchPath("objscan_bench_e2e_" + name);
  fs::create_directories(d);
  return d;
}

using objscan::testing::ReadFile;

std::string FinishedRun(const std::string& spec, double recall) {
  nlohmann::json j;
  j["scene"] = spec;
  j["terminated"] = "done";
  j["steps"] = {{{"action", "frontier"}, {"views", 2}, {"travel_m", 0.0}},
                {{"action", "nbo"}, {"views", 1}, {"travel_m", 1.5}}};
  j["metrics"] = {{"recall", recall},
                  {"precision", 0.5},
                  {"ground_truth_objects", 4},
                  {"rand_index", 0.7},
                  {"coverage_rate", 0.4},
                  {"coverage_quality", 0.2},
                  {"travel_m", 1.5},
                  {"views", 3},
                  {"per_category", {{"bed", {{"ground_truth", 1}, {"outputs", 1}, {"true_positives", 1}}}}},
                  {"coverage_per_view", {{0.1, 0.05}, {0.2, 0.1}, {0.4, 0.2}}}};
  j["timing_s"] = {{"total", 2.0}, {"navigate_sim", 5.0}};
  return j.dump();
}

TEST(BenchE2eTest, BadInputIsOneLineAndNonZero) {
  for (const char* args : {"bench --suite procedural --shard 0/2", "bench --suite procedural --methods ours,fastest",
                           "bench --suite /no/such/folder", "report /no/such/folder"}) {
    const Result r = RunObjscan(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_FALSE(r.err.empty()) << args;
    EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}

TEST(BenchE2eTest, FinishedRunsAreSkippedAndTheReportIsRebuilt) {
  const fs::path out = TempDir("resume");
  int k = 0;
  for (const char* category : {"bathroom", "bedroom", "kitchen", "living_room", "office"}) {
    for (const char* method : {"ours", "frontier"}) {
      const fs::path dir = out / "runs" / (std::string("procedural-") + category + "-1") / method;
      fs::create_directories(dir);
      std::ofstream(dir / "run.json") << FinishedRun(std::string("procedural:") + category + ":1", 0.1 * ++k);
    }
  }
  const Result r = RunObjscan("bench --suite procedural --seeds 1 --methods ours,frontier --jobs 2 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["runs_in_shard"], 10);
  EXPECT_EQ(j["runs_started"], 0);
  EXPECT_EQ(j["runs_complete_in_report"], 10);
  EXPECT_NE(r.err.find("10 done, 0 to run"), std::string::npos) << r.err;
  const std::string md = ReadFile(out / "report" / "results.md");
  EXPECT_NE(md.find("Living room"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "report" / "fig13a_coverage_travel.png"));
  // `objscan report` over the same folder rebuilds the identical results.json elsewhere.
  const Result again = RunObjscan("report " + out.string() + " --out " + (out / "again").string());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(ReadFile(out / "again" / "results.json"), ReadFile(out / "report" / "results.json"));
  fs::remove_all(out);
}

}  // namespace
