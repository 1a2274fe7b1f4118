#include "cli_util.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "objscan/common/error.h"
#include "objscan/recognition/default_database.h"

namespace objscan::app {
namespace {
bool g_bar_drawn = false;  // only the app's own terminal state; the library has no globals
}

ProgressCallback TerminalProgress(const std::string& label) {
  if (!isatty(STDERR_FILENO)) return nullptr;
  return [label](double fraction, const std::string& what) {
    const int width = 30;
    const int filled = static_cast<int>(std::lround(std::clamp(fraction, 0.0, 1.0) * width));
    std::fprintf(stderr, "\r%s [%s%s] %3d%% %-40.40s", label.c_str(), std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), static_cast<int>(std::lround(100 * fraction)),
                 what.c_str());
    std::fflush(stderr);
    g_bar_drawn = true;
  };
}

void FinishProgress() {
  if (g_bar_drawn) std::fprintf(stderr, "\n");
  g_bar_drawn = false;
}

std::uint64_t DatabaseMemoryLimitBytes(double max_database_memory_mb) {
  return recognition::DatabaseMemoryLimitBytes(max_database_memory_mb);
}

CLI::Option* AddModelPathOption(CLI::App* cmd, std::vector<std::string>* values, const std::string& for_what) {
  return cmd
      ->add_option("--model-path", *values,
                   "folders for Gazebo model:// URIs after the world's own (colon-separated, repeatable; then "
                   "$OBJSCAN_MODEL_PATH, $GAZEBO_MODEL_PATH); their parents and $GAZEBO_RESOURCE_PATH serve "
                   "relative file:// URIs" +
                       for_what)
      ->allow_extra_args(false);
}

std::string JoinModelPath(const std::vector<std::string>& values) {
  std::string joined;
  for (const std::string& v : values) {
    if (v.empty()) continue;
    joined += (joined.empty() ? "" : ":") + v;
  }
  return joined;
}

CLI::Option* AddAllowMissingFlag(CLI::App* cmd, int* count, const std::string& help) {
  return cmd->add_flag("--allow-missing", *count,
                       help + "; a world that keeps fewer than half of its models still fails unless given twice");
}

AllowMissing AllowMissingFromCount(int count) { return AllowMissing{count >= 1, count >= 2}; }

PoseArg ParsePoseArg(const std::string& text, const std::string& option_name) {
  std::vector<double> values;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v)) {
      throw InputError(option_name + " '" + text + "': '" + item + "' is not a number (expected x,y,z,yaw_deg,pitch_deg)");
    }
    values.push_back(v);
  }
  if (values.size() != 5) {
    throw InputError(option_name + " '" + text + "': expected 5 comma-separated numbers x,y,z,yaw_deg,pitch_deg");
  }
  return PoseArg{values[0], values[1], values[2], values[3], values[4]};
}

}  // namespace objscan::app
