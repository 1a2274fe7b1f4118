// The fuzz corpora and the inputs fuzzing found, replayed through the same harness as the fuzzers
// (fuzz_input.h) in the normal suite: every seed of fuzz/corpus/<target>/ is a valid file that loads,
// and every input of fuzz/regressions/<target>/ gives the answer recorded beside it in
// <input>.expected: "loads", or the loader's one-line error (the workspace folder written <ws>).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_input.h"

namespace objscan::fuzz {
namespace {
namespace fs = std::filesystem;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string LoadInput(Target target, const std::string& input) {
  return RunInput(target, reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
}

std::vector<fs::path> FilesIn(const fs::path& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_regular_file() && entry.path().extension() != ".expected") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(FuzzCorpusTest, EverySeedOfEveryTargetLoads) {
  for (Target target : AllTargets()) {
    const std::vector<fs::path> seeds = FilesIn(fs::path(OBJSCAN_FUZZ_DIR) / "corpus" / TargetName(target));
    EXPECT_GE(seeds.size(), 3u) << TargetName(target) << ": a few seeds per target";
    for (const fs::path& seed : seeds) {
      EXPECT_EQ(LoadInput(target, ReadFile(seed)), "") << seed;
    }
  }
}

TEST(FuzzRegressionTest, EveryFoundInputGivesItsRecordedAnswer) {
  int replayed = 0;
  for (Target target : AllTargets()) {
    for (const fs::path& input : FilesIn(fs::path(OBJSCAN_FUZZ_DIR) / "regressions" / TargetName(target))) {
      const fs::path expected_path = input.string() + ".expected";
      ASSERT_TRUE(fs::exists(expected_path)) << input << " has no " << expected_path.filename();
      std::string expected = ReadFile(expected_path);
      while (!expected.empty() && expected.back() == '\n') expected.pop_back();
      const std::string got = LoadInput(target, ReadFile(input));
      EXPECT_EQ(got.empty() ? "loads" : got, expected) << input;
      ++replayed;
    }
  }
  RecordProperty("replayed", replayed);
}

// The harness itself: a bad input is an InputError naming the file, a good one loads, and the
// contract check catches a message that names no file.
TEST(FuzzHarnessTest, BadInputGivesTheLoadersOneLineAndGoodInputLoads) {
  EXPECT_EQ(LoadInput(Target::kPly, "not a ply\n"), "<ws>/input.ply: bad PLY: missing 'ply' magic line");
  EXPECT_EQ(LoadInput(Target::kPly, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                              "property float z\nend_header\n1 2 3\n"),
            "");
  EXPECT_EQ(LoadInput(Target::kConfig, "#--set\nsensor.width_px=-3\n"),
            "config: sensor.width_px must be in [1.000000, 16384.000000] (got -3.000000)");
  EXPECT_EQ(LoadInput(Target::kConfig, "sensor:\n  width_px: 320\n#--set\nsensor.noise=false\n"), "");
  EXPECT_EQ(LoadInput(Target::kConfig, "#--set\nnot an assignment\n"), "--set 'not an assignment': expected key=value");
}

TEST(FuzzHarnessTest, TargetNamesRoundTrip) {
  for (Target target : AllTargets()) EXPECT_EQ(TargetFromName(TargetName(target)), target);
  EXPECT_THROW(TargetFromName("png"), std::invalid_argument);
}

}  // namespace
}  // namespace objscan::fuzz
