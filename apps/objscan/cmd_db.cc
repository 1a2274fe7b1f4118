// `objscan db`: Build, inspect and evaluate the 3D model database
// The command line is fixed by DESIGN.md; the work arrives with issue #5.
#include <cstdio>

#include "commands.h"

namespace objscan::app {

void AddDbCommand(CLI::App& root, RunFn* run) {
  auto* cmd = root.add_subcommand("db", "Build, inspect and evaluate the 3D model database");
  auto* build = cmd->add_subcommand("build", "Build a model database from a folder of models or procedurally");
  build->add_option("--models", "DIR of <category>/<name>.{obj,off,ply,dae,stl,glb}, or 'procedural'")->required();
  build->add_option("--out", "output database file F.db")->required();
  auto* info = cmd->add_subcommand("info", "Print counts of models, components and pairs per category as JSON");
  info->add_option("db", "database file")->required();
  auto* eval = cmd->add_subcommand("eval", "Evaluate retrieval accuracy and objectness on unseen models");
  eval->add_option("--db", "database file")->required();
  eval->add_option("--queries", "query source (procedural)");
  cmd->require_subcommand(1);
  cmd->callback([run] {
    *run = [] {
      std::fprintf(stderr, "objscan db: not available in this build yet (issue #5)\n");
      return 3;
    };
  });
}

}  // namespace objscan::app
