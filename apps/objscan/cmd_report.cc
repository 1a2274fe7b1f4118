// `objscan report`: Rebuild tables and plots from finished runs or bench shards
// The command line is fixed by DESIGN.md; the work arrives with issue #8.
#include <cstdio>

#include "commands.h"

namespace objscan::app {

void AddReportCommand(CLI::App& root, RunFn* run) {
  auto* cmd = root.add_subcommand("report", "Rebuild tables and plots from finished runs or bench shards");
  cmd->add_option("dirs", "run or bench folders")->required();
  cmd->callback([run] {
    *run = [] {
      std::fprintf(stderr, "objscan report: not available in this build yet (issue #8)\n");
      return 3;
    };
  });
}

}  // namespace objscan::app
