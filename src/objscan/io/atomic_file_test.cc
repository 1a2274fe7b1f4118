#include "objscan/io/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "objscan/io/test_util.h"

namespace objscan::io {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::WriteText;

std::string Read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::set<std::string> Names(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

// The pid of a process that has exited (and been reaped): no process has it right after.
long DeadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return static_cast<long>(pid);
}

TEST(AtomicFileTest, WritesTheWholeFileAndLeavesNoTemporary) {
  TempDir dir;
  const std::string path = dir.File("out.json");
  WriteText(path, "old");
  WriteFileAtomically(path, "{\"new\": true}\n");
  EXPECT_EQ(Read(path), "{\"new\": true}\n");
  EXPECT_EQ(Names(dir.path()), std::set<std::string>{"out.json"});
}

TEST(AtomicFileTest, TemporaryIsHiddenBesideTheTargetAndNamesTheWriter) {
  TempDir dir;
  const AtomicFile file(dir.File("scene.ply"));
  const fs::path temp(file.temp_path());
  EXPECT_EQ(temp.parent_path(), dir.path());
  EXPECT_EQ(temp.filename().string(), ".scene.ply.tmp." + std::to_string(static_cast<long>(::getpid())));
  long pid = 0;
  EXPECT_TRUE(IsAtomicTempName(temp.filename().string(), &pid));
  EXPECT_EQ(pid, static_cast<long>(::getpid()));
}

TEST(AtomicFileTest, UncommittedWriteLeavesTheOldFile) {
  TempDir dir;
  const std::string path = dir.File("run.json");
  WriteText(path, "complete old run");
  {
    AtomicFile file(path);
    WriteText(file.temp_path(), "half of a new ru");
    // No Commit(): the writer failed half way.
  }
  EXPECT_EQ(Read(path), "complete old run");
  EXPECT_EQ(Names(dir.path()), std::set<std::string>{"run.json"});
}

TEST(AtomicFileTest, RecognisesOnlyTemporaryNames) {
  for (const char* name : {".run.json.tmp.123", ".a.tmp.1", "..tmp.tmp.42"}) EXPECT_TRUE(IsAtomicTempName(name)) << name;
  for (const char* name : {"run.json", "run.json.tmp.123", ".run.json.tmp.", ".run.json.tmp.12a", ".tmp.123", ".hidden",
                           ".run.json.tmp123", "x.tmp.1"}) {
    EXPECT_FALSE(IsAtomicTempName(name)) << name;
  }
}

TEST(AtomicFileTest, StaleTemporariesOfDeadWritersAreRemovedLiveOnesKept) {
  TempDir dir;
  const long dead = DeadPid();
  const std::string stale = ".scene.ply.tmp." + std::to_string(dead);
  const std::string mine = ".run.json.tmp." + std::to_string(static_cast<long>(::getpid()));
  // pid 1 always exists (whoever owns it): its file is a live writer's.
  const std::string live = ".topview.png.tmp.1";
  for (const std::string& name : {stale, mine, live, std::string("scene.ply"), std::string(".keep.tmp")}) {
    WriteText(dir.File(name), "x");
  }
  EXPECT_EQ(RemoveStaleTempFiles(dir.path().string()), 1);
  EXPECT_EQ(Names(dir.path()), (std::set<std::string>{mine, live, "scene.ply", ".keep.tmp"}));
  EXPECT_EQ(RemoveStaleTempFiles(dir.File("no-such-folder")), 0);
}

TEST(AtomicFileTest, MissingFolderIsAnInputErrorNamingTheTarget) {
  TempDir dir;
  const std::string path = dir.File("missing/out.txt");
  testing::ExpectInputError([&] { WriteFileAtomically(path, "x"); }, path);
}

}  // namespace
}  // namespace objscan::io
