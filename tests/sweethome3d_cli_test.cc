// End-to-end: `objscan db build --models X.sh3f|sweethome3d` (Sweet Home 3D furniture catalogs) and the
// credits `objscan db info` lists for them; a damaged catalog is one line on stderr and exit 2.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "objscan/io/test_sweethome3d_fixture.h"
#include "run_command.h"

namespace {

namespace fs = std::filesystem;
using Result = objscan::testing::CommandResult;

Result RunObjscan(const std::string& args) { return objscan::testing::RunCommand(OBJSCAN_BINARY, args); }

using objscan::testing::CountLines;

class SweetHome3dCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = objscan::testing::ScratchPath("objscan_e2e_sh3d");
    fs::create_directories(dir_ / "catalogs");
    catalog_ = (dir_ / "catalogs" / "Test-Catalog.sh3f").string();
    objscan::io::testing::WriteSweetHome3dFixture(catalog_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
  std::string catalog_;
};

TEST_F(SweetHome3dCliTest, BuildsFromACatalogAndInfoListsTheCredits) {
  const std::string db = (dir_ / "x.db").string();
  const Result build = RunObjscan("db build --models " + catalog_ + " --out " + db);
  ASSERT_EQ(build.exit_code, 0) << build.err;
  const nlohmann::json summary = nlohmann::json::parse(build.out);
  EXPECT_EQ(summary["models"], 3);
  const nlohmann::json& sh3d = summary["sweethome3d"];
  EXPECT_EQ(sh3d["left_out_by_skip_rules"], 1);  // the sports car
  EXPECT_EQ(sh3d["left_out_unmatched"], 0);
  EXPECT_EQ(sh3d["models_per_category"]["bed"], 1);
  EXPECT_EQ(sh3d["models_per_category"]["refrigerator"], 1);
  EXPECT_EQ(sh3d["models_per_category"]["cabinet"], 1);
  ASSERT_EQ(sh3d["catalogs"].size(), 1u);
  EXPECT_EQ(sh3d["catalogs"][0]["name"], "Test catalog");
  EXPECT_EQ(sh3d["catalogs"][0]["license_text"], "Test models under CC-BY 4.0\n");

  const Result info = RunObjscan("db info " + db);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["format_version"], 5);
  // Every piece's mesh is stored with it (format 5): the database needs no catalog to give it back.
  EXPECT_EQ(j["stored_meshes"]["models"], j["models"]) << info.out;
  EXPECT_GT(j["stored_meshes"]["triangles"].get<int>(), 0) << info.out;
  const nlohmann::json& credits = j["credits"];
  ASSERT_EQ(credits.size(), 3u) << credits.dump();
  EXPECT_EQ(credits[0]["catalog"], "Test-Catalog.sh3f");
  EXPECT_EQ(credits[0]["creator"], "Alice");
  EXPECT_EQ(credits[0]["license"], "CC-BY 4.0 \xc2\xa9 Test Makers");
  EXPECT_EQ(credits[0]["models"], 1);
  EXPECT_EQ(credits[2]["creator"], "Jos\xc3\xa9");
}

TEST_F(SweetHome3dCliTest, SweetHome3dSpecReadsTheCatalogFolderFromTheEnvironment) {
  const std::string db = (dir_ / "y.db").string();
  ::setenv("OBJSCAN_SWEETHOME3D_DIR", (dir_ / "catalogs").c_str(), 1);
  const Result build = RunObjscan("db build --models sweethome3d --out " + db);
  ::setenv("OBJSCAN_SWEETHOME3D_DIR", (dir_ / "none").c_str(), 1);
  const Result missing = RunObjscan("db build --models sweethome3d --out " + db + ".2");
  ::unsetenv("OBJSCAN_SWEETHOME3D_DIR");
  ASSERT_EQ(build.exit_code, 0) << build.err;
  EXPECT_EQ(nlohmann::json::parse(build.out)["models"], 3);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(CountLines(missing.err), 1) << missing.err;
  EXPECT_NE(missing.err.find("sweethome3d-furniture"), std::string::npos) << missing.err;
}

TEST_F(SweetHome3dCliTest, TruncatedCatalogIsOneLineAndExitTwo) {
  const std::string bytes = objscan::testing::ReadFile(catalog_);
  const std::string truncated = (dir_ / "truncated.sh3f").string();
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() - 30);
  const std::string db = (dir_ / "t.db").string();
  const Result r = RunObjscan("db build --models " + truncated + " --out " + db);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(CountLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(truncated), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(db));
}

// Debian's catalogs (sweethome3d-furniture): eval accepts them as queries as build does. Slow, so
// only the smallest catalog, a few queries.
TEST_F(SweetHome3dCliTest, EvalTakesACatalogAsQueries) {
  const std::string real = "/usr/share/sweethome3d/furniture/KatorLegaz.sh3f";
  if (!fs::exists(real)) GTEST_SKIP() << "SKIPPED: " << real << " missing (install Debian's sweethome3d-furniture)";
  const std::string db = (dir_ / "e.db").string();
  ASSERT_EQ(RunObjscan("db build --models " + catalog_ + " --out " + db).exit_code, 0);
  const Result eval = RunObjscan("db eval --db " + db + " --queries " + real + " --queries-per-category 1 "
                                 "--set recognition.classifier.extra_training_databases=[]");
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  const nlohmann::json j = nlohmann::json::parse(eval.out);
  EXPECT_GT(j["query_models"].get<int>(), 0);
  EXPECT_NE(eval.err.find("Sweet Home 3D pieces left out"), std::string::npos) << eval.err;
}

}  // namespace
