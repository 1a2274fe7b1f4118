// Damaged model database files from the command line: a truncated or bit-flipped `--db` fails `run`
// and `bench` with one line naming the file and exit status 2 (before any output is written); a
// damaged database that `bench` keeps as a cache (OUT/db/no-parts.db) is rebuilt with one message,
// never used.
#include <gtest/gtest.h>

#include "run_command.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "objscan/recognition/model_database.h"

namespace {

namespace fs = std::filesystem;

using Result = objscan::testing::CommandResult;
using objscan::testing::ReadFile;

Result RunObjscan(const std::string& args) { return objscan::testing::RunCommand(OBJSCAN_BINARY, args); }

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

class DatabaseFileTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(objscan::testing::ScratchPath("objscan_database_file"));
    fs::create_directories(*dir_);
    const Result build = RunObjscan("db build --models procedural --variants 1 --out " + (*dir_ / "small.db").string());
    ASSERT_EQ(build.exit_code, 0) << build.err;
    const std::string good = ReadFile(*dir_ / "small.db");
    WriteBytes(*dir_ / "truncated.db", good.substr(0, good.size() * 2 / 3));
    std::string flipped = good;
    flipped[flipped.size() / 2] ^= 0x04;  // one bit in the payload
    WriteBytes(*dir_ / "flipped.db", flipped);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path Path(const std::string& name) { return *dir_ / name; }

  // One line on stderr, naming the file, exit status 2, nothing written to `out`.
  static void ExpectRejected(const Result& r, const fs::path& db, const fs::path& out) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(db.string()), std::string::npos) << r.err;
    EXPECT_TRUE(r.err.find("truncated") != std::string::npos || r.err.find("corrupt") != std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << out;
  }

  static inline fs::path* dir_ = nullptr;
};

TEST_F(DatabaseFileTest, DamagedDbFailsRunAndBenchWithOneLineAndExitTwo) {
  for (const char* name : {"truncated.db", "flipped.db"}) {
    const fs::path run_out = Path(std::string("run-") + name);
    ExpectRejected(RunObjscan("run --scene procedural:bathroom:1 --quiet --db " + Path(name).string() + " --out " +
                              run_out.string()),
                   Path(name), run_out);
    const fs::path bench_out = Path(std::string("bench-") + name);
    ExpectRejected(RunObjscan("bench --suite procedural --seeds 1 --methods ours --db " + Path(name).string() +
                              " --out " + bench_out.string()),
                   Path(name), bench_out);
  }
}

TEST_F(DatabaseFileTest, DamagedBenchDatabaseCacheIsRebuiltWithOneMessage) {
  // One run (shard 1 of 5: procedural-bathroom-1) of the method that needs the database without parts.
  const fs::path out = Path("bench-cache");
  fs::create_directories(out / "db");
  const std::string good = ReadFile(Path("small.db"));
  WriteBytes(out / "db" / "no-parts.db", good.substr(0, 1000));  // a database file cut short
  const Result r = RunObjscan("bench --suite procedural --seeds 1 --methods db-no-parts --shard 1/5 --jobs 1 --db " +
                              Path("small.db").string() + " --set scanner.max_steps=2 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string message = "the database is damaged, rebuilding";
  const auto at = r.err.find(message);
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(message, at + 1), std::string::npos) << "one message: " << r.err;
  EXPECT_NE(r.err.find((out / "db" / "no-parts.db").string() + ": truncated model database"), std::string::npos)
      << r.err;
  EXPECT_NO_THROW(objscan::recognition::ModelDatabase::Verify((out / "db" / "no-parts.db").string()));
  // The run used the rebuilt database: full models only.
  const objscan::recognition::ModelDatabase rebuilt =
      objscan::recognition::ModelDatabase::Load((out / "db" / "no-parts.db").string());
  EXPECT_EQ(rebuilt.entries().size(), rebuilt.models().size());
  const nlohmann::json run =
      nlohmann::json::parse(ReadFile(out / "runs" / "procedural-bathroom-1" / "db-no-parts" / "run.json"));
  EXPECT_EQ(run["database"], (out / "db" / "no-parts.db").string());
}

}  // namespace
