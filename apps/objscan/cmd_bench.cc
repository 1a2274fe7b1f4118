// `objscan bench`: Run a benchmark suite of scenes x methods and write a report
// The command line is fixed by DESIGN.md; the work arrives with issue #8.
#include <cstdio>

#include "commands.h"

namespace objscan::app {

void AddBenchCommand(CLI::App& root, RunFn* run) {
  auto* cmd = root.add_subcommand("bench", "Run a benchmark suite of scenes x methods and write a report");
  cmd->add_option("--suite", "suite NAME (procedural, oasc-dev) or a DIR of .world files")->required();
  cmd->add_option("--db", "model database file");
  cmd->add_option("--out", "output folder");
  cmd->add_option("--jobs", "parallel processes");
  cmd->add_option("--methods", "comma-separated methods");
  cmd->add_option("--shard", "run slice i/n");
  cmd->add_option("--set", "override a config key: key=value (repeatable)");
  cmd->callback([run] {
    *run = [] {
      std::fprintf(stderr, "objscan bench: not available in this build yet (issue #8)\n");
      return 3;
    };
  });
}

}  // namespace objscan::app
