#pragma once
// Helpers shared by the subcommands: progress bar on a terminal, pose strings, JSON on stdout,
// loading the effective configuration.
#include <cstdint>
#include <string>
#include <vector>

#include "objscan/common/progress.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI
namespace objscan::recognition {
struct CachedClassifierStatus;
}  // namespace objscan::recognition

namespace objscan::app {

// --model-path DIRS on `cmd`: repeatable, each value a colon-separated list of folders (as
// $GAZEBO_MODEL_PATH); `for_what` ends the help text. JoinModelPath gives the one list they make.
CLI::Option* AddModelPathOption(CLI::App* cmd, std::vector<std::string>* values, const std::string& for_what);
std::string JoinModelPath(const std::vector<std::string>& values);

// --allow-missing on `cmd`, counted: once lists what could not be loaded, twice also loads a world
// that kept fewer than half of its models. ApplyAllowMissing sets the load options from the count.
CLI::Option* AddAllowMissingFlag(CLI::App* cmd, int* count, const std::string& help);
struct AllowMissing {
  bool allow = false;
  bool insist = false;  // given twice: io::SceneLoadOptions::min_loaded_model_fraction = 0
};
AllowMissing AllowMissingFromCount(int count);

// A progress callback drawing a bar on stderr when stderr is a terminal, nothing otherwise.
ProgressCallback TerminalProgress(const std::string& label);
// Ends the bar line (if one was drawn).
void FinishProgress();

// Parses "x,y,z,yaw_deg,pitch_deg"; throws InputError naming the option on bad input.
struct PoseArg {
  double x = 0, y = 0, z = 0, yaw_deg = 0, pitch_deg = 0;
};
PoseArg ParsePoseArg(const std::string& text, const std::string& option_name);

// The built-in procedural model database: built on first use and cached (cmd_run.cc); returns its path.
std::string DefaultDatabasePath(bool verbose);
// The built-in database for a scene (recognition::UsesProceduralDatabase): procedural scenes the
// procedural one, every other scene the real one (the Sweet Home 3D library); built on first use.
std::string DefaultDatabasePathFor(const std::string& scene_spec, bool verbose);
// recognition.classifier.extra_training_databases as files: the built-in databases it names
// ("procedural", "sweethome3d") built on first use with progress, other names as they are.
std::vector<std::string> TrainingDatabasePaths(const std::vector<std::string>& names, bool verbose);
// One line on stderr when the category recognizer's cache file was damaged (and it was trained
// again) and one when the trained recognizer could not be kept there; nothing when all went well.
void ReportClassifierCache(const recognition::CachedClassifierStatus& status);

// The memory limit of a model database in bytes (ModelDatabase::Load): recognition.max_database_memory_mb,
// or when that is 0 the memory the machine has available now (MemAvailable; 0 = no limit when unknown).
std::uint64_t DatabaseMemoryLimitBytes(double max_database_memory_mb);

}  // namespace objscan::app
