// Damaged model database files from the command line: a truncated or bit-flipped `--db` fails `run`
// and `bench` with one line naming the file and exit status 2 (before any output is written); a
// damaged database that `bench` keeps as a cache (OUT/db/no-parts.db) is rebuilt with one message,
// never used; a damaged cached category recognizer is trained again with one message (`run`, `db
// eval`), and one that cannot be kept in the cache says so once.
#include <gtest/gtest.h>

#include "run_command.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "objscan/recognition/category_classifier.h"
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

// objscan with its cache folder ($OBJSCAN_CACHE_DIR) at `cache`.
Result RunObjscanWithCache(const fs::path& cache, const std::string& args) {
  return objscan::testing::RunCommand("OBJSCAN_CACHE_DIR=" + cache.string() + " " + OBJSCAN_BINARY, args);
}

// The one cached classifier file in `cache` ("" unless there is exactly one).
fs::path ClassifierFile(const fs::path& cache) {
  std::vector<fs::path> files;
  for (const auto& f : fs::directory_iterator(cache)) {
    if (f.path().filename().string().rfind("classifier-", 0) == 0) files.push_back(f.path());
  }
  return files.size() == 1 ? files[0] : fs::path();
}

// The line objscan writes when the cached classifier `file`, cut short, was trained again.
std::string TruncatedClassifierLine(const fs::path& file) {
  return "objscan: the cached category recognizer is damaged, trained it again: " + file.string() +
         ": truncated category classifier\n";
}

// The number of times `text` holds `part`.
int Occurrences(const std::string& text, const std::string& part) {
  int n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST_F(DatabaseFileTest, DamagedClassifierCacheIsTrainedAgainWithOneMessage) {
  const fs::path cache = Path("classifier-cache");
  // A short run of a database of generated models: the recognizer trains on it alone.
  auto run = [&](const fs::path& cache_dir, const std::string& out) {
    return RunObjscanWithCache(cache_dir, "run --scene procedural:bathroom:1 --quiet --db " +
                                              Path("small.db").string() + " --set scanner.max_steps=2 --out " +
                                              Path(out).string());
  };
  const std::string about = "category recognizer";
  const Result trained = run(cache, "run-classifier-trained");
  ASSERT_EQ(trained.exit_code, 0) << trained.err;
  EXPECT_EQ(Occurrences(trained.err, about), 0) << trained.err;
  const fs::path file = ClassifierFile(cache);
  ASSERT_FALSE(file.empty());
  const Result loaded = run(cache, "run-classifier-loaded");
  ASSERT_EQ(loaded.exit_code, 0) << loaded.err;
  EXPECT_EQ(Occurrences(loaded.err, about), 0) << loaded.err;

  fs::resize_file(file, 100);
  const Result repaired = run(cache, "run-classifier-damaged");
  ASSERT_EQ(repaired.exit_code, 0) << repaired.err;
  EXPECT_EQ(Occurrences(repaired.err, about), 1) << repaired.err;
  EXPECT_EQ(Occurrences(repaired.err, TruncatedClassifierLine(file)), 1) << repaired.err;
  EXPECT_NO_THROW(objscan::recognition::CategoryClassifier::Load(file.string()));  // replaced
  // The same scan as with the cached classifier.
  const nlohmann::json a = nlohmann::json::parse(loaded.out), b = nlohmann::json::parse(repaired.out);
  for (const char* key : {"views", "objects", "recall", "precision", "coverage_rate", "travel_m"}) {
    EXPECT_EQ(a[key], b[key]) << key;
  }

  // `db eval` says so too (its own cache: its options need not train the run's classifier).
  const fs::path eval_cache = Path("eval-classifier-cache");
  auto eval = [&] {
    return RunObjscanWithCache(eval_cache, "db eval --db " + Path("small.db").string() +
                                               " --queries-per-category 1 --threads 2 --set "
                                               "'recognition.classifier.extra_training_databases=[]' --set "
                                               "objectness_models_per_category=0");
  };
  const Result eval_trained = eval();
  ASSERT_EQ(eval_trained.exit_code, 0) << eval_trained.err;
  EXPECT_EQ(Occurrences(eval_trained.err, about), 0) << eval_trained.err;
  const fs::path eval_file = ClassifierFile(eval_cache);
  ASSERT_FALSE(eval_file.empty());
  fs::resize_file(eval_file, 100);
  const Result eval_repaired = eval();
  ASSERT_EQ(eval_repaired.exit_code, 0) << eval_repaired.err;
  EXPECT_EQ(Occurrences(eval_repaired.err, about), 1) << eval_repaired.err;
  EXPECT_EQ(Occurrences(eval_repaired.err, TruncatedClassifierLine(eval_file)), 1) << eval_repaired.err;

  // A cache folder that cannot be made: the run trains, and says once that it could not keep it.
  WriteBytes(Path("not-a-folder"), "x");
  const Result unwritable = run(Path("not-a-folder"), "run-classifier-unwritable");
  ASSERT_EQ(unwritable.exit_code, 0) << unwritable.err;
  EXPECT_EQ(Occurrences(unwritable.err, about), 1) << unwritable.err;
  EXPECT_EQ(Occurrences(unwritable.err, "objscan: could not keep the trained category recognizer in the cache: " +
                                            Path("not-a-folder").string() + ": cannot create the cache folder"),
            1)
      << unwritable.err;
}

}  // namespace
