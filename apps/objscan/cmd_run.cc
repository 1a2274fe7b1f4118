// `objscan run`: Scan a scene autonomously (NBO + NBV) and write a labelled reconstruction
// The command line is fixed by DESIGN.md; the work arrives with issue #7.
#include <cstdio>

#include "commands.h"

namespace objscan::app {

void AddRunCommand(CLI::App& root, RunFn* run) {
  auto* cmd = root.add_subcommand("run", "Scan a scene autonomously (NBO + NBV) and write a labelled reconstruction");
  cmd->add_option("--scene", "scene SPEC (default procedural:bedroom:1)");
  cmd->add_option("--db", "model database file (default: built-in procedural database)");
  cmd->add_option("--out", "output folder (default ./objscan-out)");
  cmd->add_option("--seed", "random seed");
  cmd->add_option("--config", "YAML config file");
  cmd->add_option("--set", "override a config key: key=value (repeatable)");
  cmd->callback([run] {
    *run = [] {
      std::fprintf(stderr, "objscan run: not available in this build yet (issue #7)\n");
      return 3;
    };
  });
}

}  // namespace objscan::app
