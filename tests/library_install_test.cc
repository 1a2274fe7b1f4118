// The library as others use it: `cmake --install` of this build into a temporary prefix gives a CMake
// package whose objscan::objscan needs only Eigen and Threads (the heavy dependencies stay inside
// libobjscan.so, no installed header includes theirs), examples/cpp configures and builds against it
// with find_package(objscan), and runs a few scanning steps with the configuration it finds relative
// to the installation; the installed objscan program finds the same folder, the build tree's the
// source tree's.
#include <gtest/gtest.h>

#include "run_command.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

namespace {

namespace fs = std::filesystem;
using objscan::testing::ReadFile;
using objscan::testing::RunCommand;

// The shell's quoting for a path.
std::string Quoted(const fs::path& p) { return "'" + p.string() + "'"; }

TEST(LibraryInstallTest, ExampleConsumerBuildsAgainstTheInstalledPackageAndScans) {
  const fs::path scratch = objscan::testing::ScratchPath("objscan_library_install");
  const fs::path prefix = scratch / "prefix";
  const std::string cmake = OBJSCAN_CMAKE_COMMAND;
  const auto install = RunCommand(cmake, "--install " + Quoted(OBJSCAN_BUILD_DIR) + " --prefix " + Quoted(prefix));
  ASSERT_EQ(install.exit_code, 0) << install.out << install.err;

  // What the installed tree holds.
  fs::path libdir;
  for (const char* candidate : {"lib", "lib64", "lib/x86_64-linux-gnu"}) {
    if (fs::exists(prefix / candidate / "cmake" / "objscan" / "objscanConfig.cmake")) libdir = prefix / candidate;
  }
  ASSERT_FALSE(libdir.empty()) << "no lib*/cmake/objscan/objscanConfig.cmake under " << prefix;
  EXPECT_TRUE(fs::exists(libdir / "libobjscan.so"));
  EXPECT_TRUE(fs::exists(prefix / "bin" / "objscan"));
  EXPECT_TRUE(fs::exists(prefix / "include" / "objscan" / "scanning" / "scanner.h"));
  EXPECT_TRUE(fs::exists(prefix / "share" / "objscan" / "config" / "default.yaml"));
  EXPECT_TRUE(fs::exists(prefix / "share" / "objscan" / "config" / "paper.yaml"));
  EXPECT_TRUE(fs::exists(prefix / "share" / "objscan" / "config" / "categories" / "default.yaml"));
  EXPECT_FALSE(fs::exists(prefix / "include" / "objscan" / "io" / "test_util.h"));  // test helpers stay out

  // Public headers only: none includes a dependency's header other than Eigen's (or gtest's).
  const std::regex foreign(R"(#\s*include\s*<(pcl|embree|octomap|assimp|yaml-cpp|png|tinyxml2|nlohmann|boost|gtest|CLI)[/.])");
  int headers = 0;
  for (const auto& entry : fs::recursive_directory_iterator(prefix / "include" / "objscan")) {
    if (entry.path().extension() != ".h") continue;
    ++headers;
    EXPECT_FALSE(std::regex_search(ReadFile(entry.path()), foreign)) << entry.path();
  }
  EXPECT_GT(headers, 100);
  // The exported target's interface names Eigen and Threads only.
  const std::string targets = ReadFile(libdir / "cmake" / "objscan" / "objscanTargets.cmake");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(targets, m, std::regex(R"(INTERFACE_LINK_LIBRARIES "([^"]*)\")"))) << targets;
  EXPECT_EQ(m[1].str(), "Eigen3::Eigen;Threads::Threads");

  // The example, configured and built against the installed package only, with the compiler (and in
  // a sanitizer build the -fsanitize flags) this build used.
  const fs::path example_build = scratch / "example";
  std::string example_flags = " -DCMAKE_CXX_COMPILER=" + Quoted(OBJSCAN_CXX_COMPILER);
  const std::string sanitize_flags = OBJSCAN_SANITIZE_FLAGS;
  if (!sanitize_flags.empty()) {
    example_flags += " -DCMAKE_CXX_FLAGS=" + Quoted(sanitize_flags) + " -DCMAKE_EXE_LINKER_FLAGS=" + Quoted(sanitize_flags);
  }
  const auto configure = RunCommand(cmake, "-S " + Quoted(fs::path(OBJSCAN_SOURCE_DIR) / "examples" / "cpp") + " -B " +
                                               Quoted(example_build) + " -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=" +
                                               Quoted(prefix) + example_flags);
  ASSERT_EQ(configure.exit_code, 0) << configure.out << configure.err;
  const auto build = RunCommand(cmake, "--build " + Quoted(example_build));
  ASSERT_EQ(build.exit_code, 0) << build.out << build.err;

  // It runs three steps of the loop with the installed configuration.
  const auto run = RunCommand("env -u OBJSCAN_CONFIG_DIR", Quoted(example_build / "objscan_example") + " 3");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(fs::path(j["config_dir"].get<std::string>()), fs::canonical(prefix / "share" / "objscan" / "config"));
  EXPECT_GE(j["scene_objects"].get<int>(), 6);  // a bedroom's furniture, floor and walls
  EXPECT_EQ(j["database_models"].get<int>(), 2);
  EXPECT_EQ(j["steps"].get<int>(), 3);
  EXPECT_GT(j["views"].get<int>(), 0);
  EXPECT_GT(j["map_points"].get<int>(), 1000);

  // The installed program finds the installed config/ (the default category map of a world), the
  // build tree's the source tree's: a category map that does not exist names the folder searched.
  const fs::path world = scratch / "empty.world";
  std::ofstream(world) << "<?xml version=\"1.0\"?>\n<sdf version=\"1.6\"><world name=\"empty\"></world></sdf>\n";
  const std::string installed_objscan = "env -u OBJSCAN_CONFIG_DIR " + Quoted(prefix / "bin" / "objscan");
  const auto found = RunCommand(installed_objscan, "scene --scene " + Quoted(world) + " --info");
  EXPECT_EQ(found.exit_code, 0) << found.err;
  const std::string missing_map = " scene --scene " + Quoted(world) + " --category-map no_such_map.yaml --info";
  const auto installed = RunCommand(installed_objscan, missing_map);
  EXPECT_NE(installed.exit_code, 0);
  EXPECT_NE(installed.err.find((fs::canonical(prefix) / "share" / "objscan" / "config").string()), std::string::npos)
      << installed.err;
  const auto built = RunCommand("env -u OBJSCAN_CONFIG_DIR " + std::string(OBJSCAN_BINARY), missing_map);
  EXPECT_NE(built.exit_code, 0);
  EXPECT_NE(built.err.find((fs::path(OBJSCAN_SOURCE_DIR) / "config").string()), std::string::npos) << built.err;
  fs::remove_all(scratch);
}

}  // namespace
