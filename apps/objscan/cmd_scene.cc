// `objscan scene`: Load a scene, print its objects, draw a top view or export its mesh
// The command line is fixed by DESIGN.md; the work arrives with issue #2.
#include <cstdio>

#include "commands.h"

namespace objscan::app {

void AddSceneCommand(CLI::App& root, RunFn* run) {
  auto* cmd = root.add_subcommand("scene", "Load a scene, print its objects, draw a top view or export its mesh");
  cmd->add_option("--scene", "scene SPEC: .world, .yaml/.json scene file, mesh, or procedural:CATEGORY:SEED")->required();
  cmd->add_flag("--info", "print objects and bounds as JSON");
  cmd->add_option("--topview", "write a top view PNG");
  cmd->add_option("--export", "write the scene mesh as PLY");
  cmd->callback([run] {
    *run = [] {
      std::fprintf(stderr, "objscan scene: not available in this build yet (issue #2)\n");
      return 3;
    };
  });
}

}  // namespace objscan::app
