#include "objscan/recognition/model_database.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <iterator>

#include "objscan/common/error.h"
#include "objscan/recognition/shape_database_suite.h"

namespace objscan::recognition {
namespace {

namespace fs = std::filesystem;

class ModelDatabaseTest : public testing::ShapeDatabaseSuite<> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("objscan_db_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<char> ReadBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::vector<char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  void WriteBytes(const fs::path& p, const std::vector<char>& bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  // Loading and verifying must both throw InputError whose message names the file.
  void ExpectRejected(const fs::path& p, const std::string& what) {
    try {
      ModelDatabase::Load(p.string());
      ADD_FAILURE() << "loaded a " << what << " database";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
    }
    try {
      ModelDatabase::Verify(p.string());
      ADD_FAILURE() << "verified a " << what << " database";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
    }
  }

  fs::path dir_;
};

TEST_F(ModelDatabaseTest, HoldsFullModelsComponentsAndPairsWithTheModelsCategory) {
  const ModelDatabase& db = *db_;
  ASSERT_EQ(db.models().size(), 5u);
  int full = 0, components = 0, pairs = 0;
  for (const auto& e : db.entries()) {
    full += e.kind == EntryKind::kFullModel;
    components += e.kind == EntryKind::kComponent;
    pairs += e.kind == EntryKind::kPair;
    EXPECT_EQ(e.category, db.models()[e.model_index].category);
    EXPECT_FALSE(e.bow.empty());
    if (e.kind == EntryKind::kFullModel) {
      EXPECT_EQ(e.keypoints.size(), 500u);
    } else {
      EXPECT_GT(e.keypoints.size(), 20u);
    }
  }
  EXPECT_EQ(full, 5);
  EXPECT_EQ(components, 5);  // the table's top and four legs
  EXPECT_EQ(pairs, 4);       // top with each leg
  for (const auto& m : db.models()) EXPECT_EQ(db.entries()[m.full_entry].kind, EntryKind::kFullModel);
}

TEST_F(ModelDatabaseTest, PartsGiveTheirPointsFromTheFullEntryWithoutCopies) {
  const ModelDatabase& db = *db_;
  int parts = 0;
  for (std::size_t i = 0; i < db.entries().size(); ++i) {
    const DatabaseEntry& e = db.entries()[i];
    const std::vector<Eigen::Vector3f> points = db.EntryPoints(static_cast<int>(i));
    if (e.kind == EntryKind::kFullModel) {
      EXPECT_EQ(points, e.points);
      continue;
    }
    ++parts;
    EXPECT_TRUE(e.points.empty()) << e.name;
    EXPECT_TRUE(e.normals.empty()) << e.name;
    const DatabaseEntry& full = db.entries()[db.models()[e.model_index].full_entry];
    ASSERT_EQ(points.size(), e.point_indices.size()) << e.name;
    for (std::size_t k = 0; k < points.size(); ++k) EXPECT_EQ(points[k], full.points[e.point_indices[k]]);
    // A pair is its two components: the table's top and a leg span the height of the table.
    if (e.kind == EntryKind::kPair) {
      EXPECT_GT(e.bounds.max_m.z() - e.bounds.min_m.z(), 0.6) << e.name;
    }
  }
  EXPECT_EQ(parts, 9);
  EXPECT_TRUE(db.EntryPoints(-1).empty());
  EXPECT_TRUE(db.EntryPoints(static_cast<int>(db.entries().size())).empty());
}

TEST_F(ModelDatabaseTest, SaveLoadRoundTrip) {
  const fs::path path = dir_ / "shapes.db";
  db_->Save(path.string());
  const ModelDatabase loaded = ModelDatabase::Load(path.string());
  ASSERT_EQ(loaded.entries().size(), db_->entries().size());
  ASSERT_EQ(loaded.models().size(), db_->models().size());
  EXPECT_EQ(loaded.vocabulary().words(), db_->vocabulary().words());
  EXPECT_EQ(loaded.settings().keypoints.num_keypoints, db_->settings().keypoints.num_keypoints);
  EXPECT_EQ(loaded.settings().descriptor.support_radius_m, db_->settings().descriptor.support_radius_m);
  for (std::size_t i = 0; i < loaded.entries().size(); ++i) {
    const auto& a = loaded.entries()[i];
    const auto& b = db_->entries()[i];
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.category, b.category);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.keypoints, b.keypoints);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.point_indices, b.point_indices);
    EXPECT_EQ(loaded.EntryPoints(static_cast<int>(i)), db_->EntryPoints(static_cast<int>(i)));
    EXPECT_EQ(a.bounds.min_m, b.bounds.min_m);
    EXPECT_EQ(a.bounds.max_m, b.bounds.max_m);
    ASSERT_EQ(a.bow.size(), b.bow.size());
    for (std::size_t k = 0; k < a.bow.size(); ++k) {
      EXPECT_EQ(a.bow[k].bin, b.bow[k].bin);
      EXPECT_EQ(a.bow[k].value, b.bow[k].value);
    }
  }
  EXPECT_TRUE(loaded.finalized());
}

TEST_F(ModelDatabaseTest, SupportHeightsRoundTrip) {
  const fs::path path = dir_ / "support.db";
  db_->Save(path.string());
  ModelDatabase db = ModelDatabase::Load(path.string());
  ASSERT_GE(db.models().size(), 2u);
  db.mutable_models()[0].support_heights_m = {0.0f, 0.72f, 0.75f};
  db.Save(path.string());
  const ModelDatabase loaded = ModelDatabase::Load(path.string());
  EXPECT_EQ(loaded.models()[0].support_heights_m, (std::vector<float>{0.0f, 0.72f, 0.75f}));
  EXPECT_TRUE(loaded.models()[1].support_heights_m.empty());
}

// Format 5: each model's mesh is stored; a database that has none for a model (built from scans)
// gives an empty one back; a triangle naming a vertex the mesh lacks is a corrupt database.
TEST_F(ModelDatabaseTest, StoredMeshesRoundTripAndBadIndicesAreRejected) {
  const fs::path path = dir_ / "meshes.db";
  db_->Save(path.string());
  ModelDatabase db = ModelDatabase::Load(path.string());
  ASSERT_GE(db.models().size(), 2u);
  for (const auto& m : db.models()) EXPECT_TRUE(m.mesh.Empty()) << m.name << ": built from scans";
  const geometry::TriangleMesh box = geometry::MakeBox(Eigen::Vector3d(0.0, -0.2, 0.0), Eigen::Vector3d(0.5, 0.2, 0.9));
  db.mutable_models()[0].mesh = box;
  db.Save(path.string());
  const ModelDatabase loaded = ModelDatabase::Load(path.string());
  EXPECT_EQ(loaded.models()[0].mesh.vertices, box.vertices);
  EXPECT_EQ(loaded.models()[0].mesh.triangles, box.triangles);
  EXPECT_TRUE(loaded.models()[1].mesh.Empty());

  db.mutable_models()[0].mesh.triangles[5] = Eigen::Vector3i(0, 1, 8);  // 8 vertices: 0..7
  db.Save(path.string());
  // (Verify checks the header and checksum only: a well-saved file passes it; parsing finds the index.)
  try {
    ModelDatabase::Load(path.string());
    ADD_FAILURE() << "loaded a triangle with an out-of-range index";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path.string() + ": corrupt model database (model mesh triangle index)");
  }
}

TEST_F(ModelDatabaseTest, RejectsCorruptTruncatedForeignAndOldFiles) {
  const fs::path good = dir_ / "good.db";
  db_->Save(good.string());
  const std::vector<char> bytes = ReadBytes(good);
  EXPECT_NO_THROW(ModelDatabase::Verify(good.string()));

  ExpectRejected(dir_ / "missing.db", "missing");
  // One flipped bit anywhere (header or payload) is caught.
  for (std::size_t at : {std::size_t{9}, std::size_t{14}, std::size_t{21}, std::size_t{40}, bytes.size() - 1}) {
    std::vector<char> flipped = bytes;
    flipped[at] ^= 0x01;
    WriteBytes(dir_ / "flipped.db", flipped);
    ExpectRejected(dir_ / "flipped.db", "bit-flipped at " + std::to_string(at));
  }

  std::vector<char> corrupt = bytes;
  corrupt[corrupt.size() / 2] ^= 0x5A;
  WriteBytes(dir_ / "corrupt.db", corrupt);
  ExpectRejected(dir_ / "corrupt.db", "corrupt");

  for (std::size_t cut : {bytes.size() - 1, bytes.size() / 3, std::size_t{20}, std::size_t{5}}) {
    WriteBytes(dir_ / "truncated.db", std::vector<char>(bytes.begin(), bytes.begin() + cut));
    ExpectRejected(dir_ / "truncated.db", "truncated");
  }

  WriteBytes(dir_ / "foreign.db", std::vector<char>{'s', 'o', 'l', 'i', 'd', ' ', 'f', 'o', 'o', '\n', 0, 0});
  ExpectRejected(dir_ / "foreign.db", "foreign");

  std::vector<char> old = bytes;
  old[8] = 0;  // version 0 (little-endian u32 after the 8-byte magic)
  WriteBytes(dir_ / "old.db", old);
  ExpectRejected(dir_ / "old.db", "old");
  try {
    ModelDatabase::Load((dir_ / "old.db").string());
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("version"), std::string::npos) << e.what();
  }
  // The format before stored meshes (4) is named, with what to do.
  old[8] = 4;
  WriteBytes(dir_ / "old.db", old);
  ExpectRejected(dir_ / "old.db", "version 4");
  try {
    ModelDatabase::Load((dir_ / "old.db").string());
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "old.db").string() + ": model database format version 4, this objscan "
                                     "reads version 5 (rebuild it with objscan db build)");
  }

  std::vector<char> trailing = bytes;
  trailing.push_back(0);
  WriteBytes(dir_ / "trailing.db", trailing);
  ExpectRejected(dir_ / "trailing.db", "trailing");
}

// Settings a file can hold but no valid database has: more height bands than the histogram's bins can
// number (found by fuzzing: the cell count overflowed int) is a corrupt database naming the key.
TEST_F(ModelDatabaseTest, SettingsBeyondTheirBoundsAreRejected) {
  const fs::path path = dir_ / "bands.db";
  const int bands = db_->settings().bow.height_bands;
  db_->mutable_settings().bow.height_bands = 1660944386;  // Save writes settings as they are
  db_->Save(path.string());
  db_->mutable_settings().bow.height_bands = bands;
  try {
    ModelDatabase::Load(path.string());
    ADD_FAILURE() << "loaded a database with 1660944386 height bands";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path.string() + ": corrupt model database (settings: config: "
                                                      "recognition.bow.height_bands must be in [1, 100])");
  }
}

TEST_F(ModelDatabaseTest, DatabaseLargerThanTheMemoryLimitIsRejectedBeforeItIsRead) {
  const fs::path good = dir_ / "good.db";
  db_->Save(good.string());
  const std::uint64_t need = fs::file_size(good) * ModelDatabase::kMemoryPerFileByte;
  EXPECT_NO_THROW(ModelDatabase::Load(good.string(), need));
  for (const bool verify : {false, true}) {
    try {
      if (verify) {
        ModelDatabase::Verify(good.string(), need - 1);
      } else {
        ModelDatabase::Load(good.string(), need - 1);
      }
      ADD_FAILURE() << "a database over the memory limit was accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(good.string() + ": the model database needs about", 0), 0u) << message;
      EXPECT_NE(message.find("recognition.max_database_memory_mb"), std::string::npos) << message;
    }
  }
  // The limit is checked from the file size alone: a file that is not a database is refused for its size.
  std::vector<char> junk(4096, 'x');
  WriteBytes(dir_ / "junk.db", junk);
  try {
    ModelDatabase::Load((dir_ / "junk.db").string(), 1024);
    ADD_FAILURE() << "loaded junk";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_database_memory_mb"), std::string::npos) << e.what();
  }
}

TEST_F(ModelDatabaseTest, SaveFailureLeavesNoFile) {
  const fs::path path = dir_ / "no_such_dir" / "x.db";
  EXPECT_THROW(db_->Save(path.string()), InputError);
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace objscan::recognition
