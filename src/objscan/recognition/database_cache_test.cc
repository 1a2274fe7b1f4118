#include "objscan/recognition/database_cache.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "objscan/common/error.h"
#include "objscan/recognition/shape_database_suite.h"

namespace objscan::recognition {
namespace {

namespace fs = std::filesystem;

class DatabaseCacheTest : public testing::ShapeDatabaseSuite<> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("objscan_db_cache_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    path_ = (dir_ / "procedural.db").string();
    source_ = (dir_ / "source.db").string();
    db_->Save(source_);  // what the build gives (a ModelDatabase is move-only)
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<char> ReadBytes() const {
    std::ifstream in(path_, std::ios::binary);
    return std::vector<char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  void WriteBytes(const std::vector<char>& bytes) const {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  // Ensures the cache, counting builds and messages.
  CachedDatabaseStatus Ensure() {
    return EnsureCachedDatabase(
        path_,
        [this] {
          ++builds_;
          return ModelDatabase::Load(source_);
        },
        [this](const CachedDatabaseStatus&) { ++messages_; });
  }

  fs::path dir_;
  std::string path_, source_;
  int builds_ = 0, messages_ = 0;
};

TEST_F(DatabaseCacheTest, BuildsOnceThenUsesTheFile) {
  const CachedDatabaseStatus first = Ensure();
  EXPECT_TRUE(first.built);
  EXPECT_TRUE(first.damage.empty());
  const std::vector<char> bytes = ReadBytes();
  const CachedDatabaseStatus second = Ensure();
  EXPECT_FALSE(second.built);
  EXPECT_EQ(builds_, 1);
  EXPECT_EQ(messages_, 1);
  EXPECT_EQ(ReadBytes(), bytes);
  EXPECT_EQ(ModelDatabase::Load(path_).entries().size(), db_->entries().size());
}

TEST_F(DatabaseCacheTest, TruncatedOrBitFlippedCacheIsRebuiltNeverUsed) {
  Ensure();
  const std::vector<char> good = ReadBytes();
  ASSERT_GT(good.size(), 1000u);
  std::vector<std::vector<char>> damaged;
  for (std::size_t cut : {good.size() - 1, good.size() / 2, std::size_t{30}, std::size_t{0}}) {
    damaged.emplace_back(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut));
  }
  for (std::size_t at : {std::size_t{9}, std::size_t{20}, good.size() / 3, good.size() - 1}) {
    std::vector<char> flipped = good;
    flipped[at] ^= 0x10;  // one bit, in the version, the checksum and the payload
    damaged.push_back(flipped);
  }
  for (std::size_t k = 0; k < damaged.size(); ++k) {
    WriteBytes(damaged[k]);
    builds_ = messages_ = 0;
    const CachedDatabaseStatus status = Ensure();
    EXPECT_TRUE(status.built) << "damage " << k;
    EXPECT_EQ(builds_, 1) << "damage " << k;
    EXPECT_EQ(messages_, 1) << "damage " << k;
    EXPECT_NE(status.damage.find(path_), std::string::npos) << status.damage;
    EXPECT_EQ(status.damage.find('\n'), std::string::npos) << status.damage;
    EXPECT_EQ(ReadBytes(), good) << "damage " << k << ": the rebuilt file is the database the build gave";
  }
}

TEST_F(DatabaseCacheTest, FailedBuildLeavesNoCacheFile) {
  EXPECT_THROW(EnsureCachedDatabase(path_, []() -> ModelDatabase { throw InputError("model source missing"); }),
               InputError);
  EXPECT_FALSE(fs::exists(path_));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1) << "only source.db";
}

}  // namespace
}  // namespace objscan::recognition
