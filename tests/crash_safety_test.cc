// Crash safety of the outputs: `objscan run` and `objscan bench` killed with SIGKILL at moments drawn
// from a fixed-seed generator (and right after given output files appear, so some kills land while
// the outputs are being written) leave only complete, readable files (every file is written
// atomically: io/atomic_file.h), no temporary that looks like an output, a run.json only beside
// every other file of its run, and `bench` re-run on the same folder resumes to the results of an
// uninterrupted bench (apart from timings).
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "run_command.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "objscan/io/atomic_file.h"
#include "objscan/io/ply.h"
#include "objscan/io/png.h"
#include "objscan/recognition/model_database.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using objscan::testing::ReadFile;

// The files of a finished run folder besides run.json (run_output.h; procedural rooms have ground
// truth, hence coverage.ply).
const char* const kRunFiles[] = {"scene.ply",       "models.ply",  "coverage.ply", "trajectory.csv",
                                 "trajectory.tum",  "categories.json", "topview.png",  "navmap.png"};

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// Starts the objscan program with `args` as the leader of a new process group (so the bench and its
// runs can be killed together, as a crash or the OOM killer would), stdout to `stdout_path`.
pid_t Start(const std::vector<std::string>& args, const fs::path& stdout_path) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    const int out = ::open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open((stdout_path.string() + ".err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(out, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(OBJSCAN_BINARY));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(OBJSCAN_BINARY, argv.data());
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also here: the group must exist before a kill, whichever runs first
  return pid;
}

// Waits for `pid`: its exit code, or -signal.
int Wait(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? -WTERMSIG(status) : -1;
}

// SIGKILL to the whole group, then waits until none of it is left (the test is the subreaper of the
// bench's runs, so their zombies are reaped here).
void KillGroup(pid_t pgid) {
  ::kill(-pgid, SIGKILL);
  const auto deadline = Clock::now() + std::chrono::seconds(30);
  while (Clock::now() < deadline) {
    int status = 0;
    while (::waitpid(-1, &status, WNOHANG) > 0) {
    }
    if (::kill(-pgid, 0) != 0 && errno == ESRCH) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ADD_FAILURE() << "process group " << pgid << " still alive 30 s after SIGKILL";
}

// How a trial ends the process: after `delay_s`, or, with a trigger, `delay_s` after the trigger
// first holds (polled every half millisecond).
struct Kill {
  double delay_s = 0.0;
  std::function<bool()> trigger;
};

// The first call of a trigger is right after the start, long before the program writes anything: it
// notes what is there, so files left by earlier trials do not count.

// `path` is written anew (a new file renamed over it: its inode changes).
std::function<bool()> FileWritten(const fs::path& path) {
  auto before = std::make_shared<std::optional<ino_t>>();
  auto first = std::make_shared<bool>(true);
  return [path, before, first] {
    struct stat st {};
    const bool exists = ::stat(path.c_str(), &st) == 0;
    if (*first) {
      *first = false;
      if (exists) *before = st.st_ino;
      return false;
    }
    return exists && (!before->has_value() || **before != st.st_ino);
  };
}

// A new AtomicFile temporary (of `target` when given) appears in `folder`: an output is being written.
std::function<bool()> TemporaryAppears(const fs::path& folder, const std::string& target = "") {
  auto before = std::make_shared<std::set<std::string>>();
  auto first = std::make_shared<bool>(true);
  return [folder, target, before, first] {
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (!objscan::io::IsAtomicTempName(name) || name.rfind("." + target, 0) != 0) continue;
      if (*first) {
        before->insert(name);
      } else if (!before->count(name)) {
        return true;
      }
    }
    *first = false;
    return false;
  };
}

// Runs the command and kills it as `kill` says; true when it was killed (false: it finished first).
bool StartAndKill(const std::vector<std::string>& args, const fs::path& stdout_path, const Kill& kill,
                  double timeout_s) {
  const pid_t pid = Start(args, stdout_path);
  const auto start = Clock::now();
  const auto delay = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kill.delay_s));
  auto kill_at = kill.trigger ? Clock::time_point::max() : start + delay;
  while (true) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;  // finished before the kill
    const auto now = Clock::now();
    if (kill.trigger && kill_at == Clock::time_point::max() && kill.trigger()) kill_at = now + delay;
    if (now >= kill_at || Seconds(now - start) > timeout_s) {
      KillGroup(pid);
      return true;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
}

// run.json or results.json without what depends on the machine: timings, memory, CPU time.
void StripTimings(nlohmann::json* j) {
  if (j->is_object()) {
    for (const char* key : {"timing_s", "timing_ms", "compute_s", "cpu_s", "peak_rss_mb", "resources", "table3",
                            "wall_s"}) {
      j->erase(key);
    }
  }
  if (j->is_structured()) {
    for (auto& v : *j) StripTimings(&v);
  }
}

nlohmann::json ComparableJson(const fs::path& path) {
  nlohmann::json j = nlohmann::json::parse(ReadFile(path));
  StripTimings(&j);
  return j;
}

// Every file below `root` is complete and readable by its kind; hidden files are only AtomicFile
// temporaries (a killed writer's, never taken for outputs); a folder with run.json holds every file
// of the run. `temporaries` counts the temporaries found.
void ExpectOnlyCompleteFiles(const fs::path& root, const std::string& when, int* temporaries) {
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const fs::path& p = entry.path();
    const std::string name = p.filename().string();
    if (entry.is_directory()) {
      if (fs::exists(p / "run.json")) {
        for (const char* file : kRunFiles) EXPECT_TRUE(fs::exists(p / file)) << when << ": " << p << " has run.json but no " << file;
      }
      continue;
    }
    SCOPED_TRACE(when + ": " + p.string());
    if (name[0] == '.') {
      EXPECT_TRUE(objscan::io::IsAtomicTempName(name)) << "unexpected hidden file";
      ++*temporaries;
      continue;
    }
    // The logs of bench's runs, written as they go: not outputs.
    if (name == "stdout.txt" || name == "stderr.txt") continue;
    const std::string ext = p.extension().string();
    const std::string text = ReadFile(p);
    if (ext == ".json") {
      const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
      EXPECT_TRUE(j.is_object()) << "not a complete JSON object (" << text.size() << " bytes)";
    } else if (ext == ".ply") {
      EXPECT_NO_THROW(objscan::io::ReadPly(p.string()));
    } else if (ext == ".png") {
      EXPECT_NO_THROW(objscan::io::ReadPngRgb(p.string()));
    } else if (ext == ".svg") {
      EXPECT_EQ(text.rfind("<svg", 0), 0u);
      EXPECT_NE(text.find("</svg>"), std::string::npos);
    } else if (ext == ".md") {
      EXPECT_TRUE(!text.empty() && text.back() == '\n');
    } else if (ext == ".csv") {
      ASSERT_TRUE(!text.empty() && text.back() == '\n');
      // Every row has the header's number of fields.
      std::istringstream lines(text);
      std::string line;
      std::getline(lines, line);
      const auto fields = std::count(line.begin(), line.end(), ',');
      while (std::getline(lines, line)) EXPECT_EQ(std::count(line.begin(), line.end(), ','), fields) << line;
    } else if (ext == ".tum") {
      ASSERT_TRUE(!text.empty() && text.back() == '\n');
      // '#' comments, then "timestamp tx ty tz qx qy qz qw" rows with unit quaternions.
      std::istringstream lines(text);
      for (std::string line; std::getline(lines, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream row(line);
        double v[8];
        for (double& x : v) ASSERT_TRUE(static_cast<bool>(row >> x)) << line;
        EXPECT_NEAR(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7], 1.0, 1e-6) << line;
      }
    } else if (ext == ".db") {
      EXPECT_NO_THROW(objscan::recognition::ModelDatabase::Verify(p.string()));
    } else {
      ADD_FAILURE() << "an output nobody expects";
    }
  }
}

int CountTemporaries(const fs::path& root) {
  int n = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    n += objscan::io::IsAtomicTempName(entry.path().filename().string());
  }
  return n;
}

// A scratch folder holding small.db (one procedural model per category: a short build).
fs::path ScratchWithSmallDatabase(const std::string& name) {
  const fs::path dir = objscan::testing::ScratchPath(name);
  fs::create_directories(dir);
  const auto build =
      objscan::testing::RunCommand(OBJSCAN_BINARY, "db build --models procedural --variants 1 --out " + (dir / "small.db").string());
  EXPECT_EQ(build.exit_code, 0) << build.err;
  return dir;
}

// A coarse camera (160 x 120, the default field of view) and a few steps keep each run to seconds: the
// test is about the files, not about the scan.
const std::vector<std::string> kFastRunSets = {
    "--set", "sensor.width_px=160", "--set", "sensor.height_px=120", "--set", "sensor.fx_px=131.25",
    "--set", "sensor.fy_px=131.25", "--set", "sensor.cx_px=79.5",   "--set", "sensor.cy_px=59.5",
    "--set", "scanner.max_steps=3"};

std::vector<std::string> Concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

class CrashSafetyTest : public ::testing::Test {
 protected:
  // The bench's runs are its children; killed with it, they become ours to reap.
  void SetUp() override { ASSERT_EQ(::prctl(PR_SET_CHILD_SUBREAPER, 1), 0); }
};

TEST_F(CrashSafetyTest, KilledRunLeavesOnlyCompleteFiles) {
  const fs::path dir = ScratchWithSmallDatabase("objscan_crash_run");
  ASSERT_TRUE(fs::exists(dir / "small.db"));
  auto args = [&](const fs::path& out) {
    return Concat({"run", "--scene", "procedural:bathroom:1", "--db", (dir / "small.db").string(), "--seed", "2",
                   "--quiet", "--out", out.string()},
                  kFastRunSets);
  };
  const auto start = Clock::now();
  ASSERT_EQ(Wait(Start(args(dir / "reference"), dir / "reference.out")), 0) << ReadFile(dir / "reference.out.err");
  const double run_s = Seconds(Clock::now() - start);
  const nlohmann::json reference = ComparableJson(dir / "reference" / "run.json");

  // Kills at moments of the run (most of it is scanning; the outputs come in its last part), right
  // after given outputs appear, and while an output is half written (its temporary exists).
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> moment(0.3 * run_s, 1.0 * run_s), jitter(0.0, 0.004);
  const fs::path out = dir / "killed";
  std::vector<Kill> kills;
  for (int k = 0; k < 2; ++k) kills.push_back({moment(rng), nullptr});
  kills.push_back({0.0, TemporaryAppears(out)});
  for (const char* file : {"scene.ply", "topview.png"}) kills.push_back({jitter(rng), FileWritten(out / file)});
  kills.push_back({0.0, TemporaryAppears(out)});
  int killed = 0, killed_while_writing = 0, temporaries = 0;
  for (std::size_t t = 0; t < kills.size(); ++t) {
    const std::string when = "trial " + std::to_string(t);
    const bool was_killed = StartAndKill(args(out), dir / "killed.out", kills[t], 4 * run_s + 30);
    killed += was_killed;
    if (!fs::exists(out)) continue;
    ExpectOnlyCompleteFiles(out, when, &temporaries);
    if (fs::exists(out / "run.json")) {
      EXPECT_EQ(ComparableJson(out / "run.json"), reference) << when;
    } else {
      killed_while_writing += was_killed && kills[t].trigger != nullptr;
    }
  }
  EXPECT_GE(killed, 4) << "most trials must end in a kill";
  EXPECT_GE(killed_while_writing, 1) << "no kill landed between the first output and run.json";
  std::printf("run: %.1f s, %d of %zu trials killed, %d while writing outputs, %d temporaries left by kills\n", run_s,
              killed, kills.size(), killed_while_writing, temporaries);

  // Run again into the killed folder: the same run, and no temporary left (also not one planted as a
  // dead writer's: the pid of a process that has exited).
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  Wait(dead);
  const fs::path planted = out / (".scene.ply.tmp." + std::to_string(dead));
  std::ofstream(planted) << "half a PLY";
  ASSERT_EQ(Wait(Start(args(out), dir / "final.out")), 0) << ReadFile(dir / "final.out.err");
  EXPECT_FALSE(fs::exists(planted));
  EXPECT_EQ(ComparableJson(out / "run.json"), reference);
  for (const char* file : kRunFiles) EXPECT_TRUE(fs::exists(out / file)) << file;
  EXPECT_EQ(CountTemporaries(out), 0);
  fs::remove_all(dir);
}

TEST_F(CrashSafetyTest, KilledBenchLeavesOnlyCompleteFilesAndResumesToTheSameResults) {
  const fs::path dir = ScratchWithSmallDatabase("objscan_crash_bench");
  ASSERT_TRUE(fs::exists(dir / "small.db"));
  // The procedural suite, one room per category, each run a few steps.
  auto args = [&](const fs::path& out) {
    return Concat({"bench", "--suite", "procedural", "--seeds", "1", "--methods", "ours", "--jobs", "2", "--db",
                   (dir / "small.db").string(), "--out", out.string()},
                  kFastRunSets);
  };
  const fs::path reference = dir / "reference";
  const auto start = Clock::now();
  ASSERT_EQ(Wait(Start(args(reference), dir / "reference.out")), 0) << ReadFile(dir / "reference.out.err");
  const double bench_s = Seconds(Clock::now() - start);
  std::vector<fs::path> run_dirs;
  for (const auto& scene : fs::directory_iterator(reference / "runs")) run_dirs.push_back(fs::relative(scene.path() / "ours", reference));
  ASSERT_EQ(run_dirs.size(), 5u);

  // Kills while the runs go (each trial resumes what the earlier ones finished), then a resume to the
  // end; then kills while the report of the finished runs is being written, then one more resume.
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> moment(0.1 * bench_s, 0.5 * bench_s), jitter(0.0, 0.004);
  const fs::path out = dir / "killed";
  const fs::path report = out / "report";
  int killed = 0, temporaries = 0;
  auto trial = [&](const Kill& kill, const std::string& when) {
    killed += StartAndKill(args(out), dir / "killed.out", kill, 4 * bench_s + 30);
    if (!fs::exists(out)) return;
    ExpectOnlyCompleteFiles(out, when, &temporaries);
    for (const auto& run : run_dirs) {
      if (fs::exists(out / run / "run.json")) {
        EXPECT_EQ(ComparableJson(out / run / "run.json"), ComparableJson(reference / run / "run.json")) << when << " " << run;
      }
    }
  };
  auto resume = [&](int expected_to_start) {
    ASSERT_EQ(Wait(Start(args(out), dir / "final.out")), 0) << ReadFile(dir / "final.out.err");
    const nlohmann::json summary = nlohmann::json::parse(ReadFile(dir / "final.out"));
    EXPECT_EQ(summary["runs_started"].get<int>(), expected_to_start);
    EXPECT_EQ(summary["runs_complete_in_report"].get<int>(), 5);
    EXPECT_EQ(summary["runs_failed"].get<int>(), 0);
    for (const auto& run : run_dirs) {
      EXPECT_EQ(ComparableJson(out / run / "run.json"), ComparableJson(reference / run / "run.json")) << run;
      EXPECT_FALSE(fs::exists(out / run / "failed.json")) << run;
    }
    EXPECT_EQ(ComparableJson(report / "results.json"), ComparableJson(reference / "report" / "results.json"));
    EXPECT_EQ(CountTemporaries(out), 0);
  };
  for (int k = 0; k < 2; ++k) trial({moment(rng), nullptr}, "run trial " + std::to_string(k));
  // Only the unfinished runs start again, and the results are the uninterrupted bench's.
  int finished = 0;
  for (const auto& run : run_dirs) finished += fs::exists(out / run / "run.json");
  resume(5 - finished);
  const int report_killed_before = killed;
  trial({0.0, TemporaryAppears(report)}, "report trial 0");  // results.json half written
  trial({jitter(rng), TemporaryAppears(report, "fig10a_rand_index.svg")}, "report trial 1");  // among the plots
  resume(0);
  EXPECT_GE(killed, 3);
  EXPECT_GE(killed - report_killed_before, 1) << "no kill landed while the report was written";
  std::printf("bench: %.1f s, %d of 4 trials killed, %d runs finished before the resume, %d temporaries left by kills\n",
              bench_s, killed, finished, temporaries);
  fs::remove_all(dir);
}

}  // namespace
