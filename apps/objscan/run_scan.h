#pragma once
// The part of `objscan run` after the robot is chosen: scan with a platform, evaluate against the
// scene's ground truth when there is one, write the output folder and print the summary line. The
// simulator (cmd_run.cc) and the ROS node (ros/objscan_ros_node.cc) share it, so a run over ROS
// writes the same files as a run in one process.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "objscan/platform/platform.h"
#include "objscan/recognition/model_database.h"
#include "objscan/scanning/scanner.h"
#include "objscan/scanning/system_config.h"
#include "objscan/world/scene.h"

namespace CLI {
class App;
}  // namespace CLI

namespace objscan::app {

// The options every program that scans takes for its configuration, as `objscan run` spells them.
struct ConfigArgs {
  std::string config_file;         // --config
  std::vector<std::string> sets;   // --set key=value...
  std::vector<std::string> model_path;  // --model-path, repeatable (scene.model_path)
  std::string category_map;        // --category-map (scene.category_map)
  bool doors_open = false;         // --doors-open (scene.doors_open)
};
void AddConfigOptions(CLI::App* app, ConfigArgs* args);
// The effective configuration (scanning::LoadSystemConfig); throws InputError naming the key.
scanning::SystemConfig LoadRunConfig(const ConfigArgs& args);

// Runs `run` as a program's main does: bad input (InputError) is one line "<program>: error: ..." and
// exit code 2, any other failure one such line and 1.
int ReportErrors(const char* program, const std::function<int()>& run);

// The model database of a run, loaded and checked (an empty database is bad input), with the
// built-in training databases its category recognizer also reads built now (with progress).
struct RunDatabase {
  std::string path;
  recognition::ModelDatabase database;
};
// `db_path` empty: the built-in database for `scene_spec` (DefaultDatabasePathFor).
RunDatabase LoadRunDatabase(const std::string& db_path, const std::string& scene_spec,
                            const scanning::SystemConfig& config, bool quiet);

struct ScanRunInputs {
  const scanning::SystemConfig* config = nullptr;
  const RunDatabase* database = nullptr;
  // The scene's ground truth for evaluation (metrics, gt_instance); null: none (a real robot's room).
  const world::Scene* scene = nullptr;
  std::string scene_spec;  // run.json `scene`
  std::uint64_t seed = 1;
  std::string out;
  bool quiet = false;
  bool save_frames = false;
  std::string program = "objscan run";  // the prefix of warnings on stderr
  // Called after every step of the scan and once after the report stage (to show progress
  // elsewhere, e.g. on ROS topics); may be empty.
  std::function<void(const scanning::Scanner& scanner, const scanning::RunRecord& record, bool finished)> on_step;
};

// Scans with `platform` from where it stands, writes OUT/ (eval::WriteRunOutputs) and prints the
// JSON summary line on stdout. Returns the exit code (0).
int ScanAndWrite(const ScanRunInputs& in, platform::Platform* platform);

}  // namespace objscan::app
