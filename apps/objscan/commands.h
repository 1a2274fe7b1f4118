#pragma once
// Each subcommand lives in its own cmd_*.cc and registers itself on the root app. A registration
// sets *run to the work to do when that subcommand was chosen; main() runs it and turns exceptions
// into one line on stderr and a non-zero exit.
#include <CLI/CLI.hpp>
#include <functional>

namespace objscan::app {

using RunFn = std::function<int()>;

void AddSceneCommand(CLI::App& root, RunFn* run);
void AddRenderCommand(CLI::App& root, RunFn* run);
void AddDbCommand(CLI::App& root, RunFn* run);
void AddRunCommand(CLI::App& root, RunFn* run);
void AddBenchCommand(CLI::App& root, RunFn* run);
void AddReportCommand(CLI::App& root, RunFn* run);
void AddViewCommand(CLI::App& root, RunFn* run);

}  // namespace objscan::app
