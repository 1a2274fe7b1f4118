// Results must not depend on the number of threads: the database build (`db build --threads`) and a
// short scan of a procedural room with every parallel stage of a run on 1 thread (sensor.threads,
// nbv.threads, scanner.threads for the recognition queries, eval.threads for the evaluation's ray
// casting) and on 2 give the same files, apart from the timings, resources and the thread counts
// in the effective config.
#include <gtest/gtest.h>

#include "run_command.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace {

namespace fs = std::filesystem;

using Result = objscan::testing::CommandResult;
using objscan::testing::ReadFile;

Result RunObjscan(const std::string& args) { return objscan::testing::RunCommand(OBJSCAN_BINARY, args); }

// The keys of every thread count a run reads (each a parallel stage).
const char* const kThreadKeys[] = {"sensor.threads", "nbv.threads", "scanner.threads", "eval.threads"};

std::string ThreadSets(int threads) {
  std::string sets;
  for (const char* key : kThreadKeys) sets += std::string(" --set ") + key + "=" + std::to_string(threads);
  return sets;
}

// run.json without what depends on the machine (timings, memory, CPU time) and on the thread counts
// themselves (the effective config records them).
nlohmann::json Comparable(nlohmann::json j) {
  j.erase("timing_s");
  j.erase("peak_rss_mb");
  j.erase("cpu_s");
  for (auto& step : j["steps"]) step.erase("timing_ms");
  for (const char* key : kThreadKeys) {
    const std::string k(key);
    const std::string section = k.substr(0, k.find('.'));
    EXPECT_TRUE(j["config"][section].contains("threads")) << key << " is not in run.json's config";
    j["config"][section].erase("threads");
  }
  return j;
}

TEST(ThreadDeterminismTest, OneAndTwoThreadsGiveTheSameDatabaseAndRun) {
  const fs::path dir = objscan::testing::ScratchPath("objscan_thread_determinism");
  fs::create_directories(dir);
  // One model per category keeps the builds short; scanned on 1 and on 2 threads.
  const std::string db1 = (dir / "threads1.db").string(), db2 = (dir / "threads2.db").string();
  for (const auto& [db, threads] : {std::pair{db1, 1}, std::pair{db2, 2}}) {
    const Result build = RunObjscan("db build --models procedural --variants 1 --threads " + std::to_string(threads) +
                                    " --out " + db);
    ASSERT_EQ(build.exit_code, 0) << build.err;
  }
  const std::string db_bytes = ReadFile(db1);
  ASSERT_GT(db_bytes.size(), 10000u);
  EXPECT_TRUE(db_bytes == ReadFile(db2)) << "db build --threads 1 and --threads 2 differ";

  const std::string common = "run --scene procedural:kitchen:2 --db " + db1 +
                             " --seed 4 --quiet --set scanner.max_steps=10 --out ";
  const Result one = RunObjscan(common + (dir / "t1").string() + ThreadSets(1));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const Result two = RunObjscan(common + (dir / "t2").string() + ThreadSets(2));
  ASSERT_EQ(two.exit_code, 0) << two.err;

  const nlohmann::json run1 = nlohmann::json::parse(ReadFile(dir / "t1" / "run.json"));
  const nlohmann::json run2 = nlohmann::json::parse(ReadFile(dir / "t2" / "run.json"));
  // The runs did what they were told (so the comparison is not between two empty runs).
  EXPECT_EQ(run1["config"]["nbv"]["threads"], 1);
  EXPECT_EQ(run2["config"]["nbv"]["threads"], 2);
  EXPECT_GE(run1["steps"].size(), 3u);
  EXPECT_GT(run1["metrics"]["views"].get<int>(), 0);
  EXPECT_EQ(Comparable(run1), Comparable(run2));
  // The other files hold no timing: byte for byte.
  for (const char* file : {"scene.ply", "models.ply", "coverage.ply", "trajectory.csv", "trajectory.tum",
                           "categories.json", "topview.png", "navmap.png"}) {
    const std::string a = ReadFile(dir / "t1" / file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_TRUE(a == ReadFile(dir / "t2" / file)) << file << " differs between 1 and 2 threads";
  }
  fs::remove_all(dir);
}

}  // namespace
