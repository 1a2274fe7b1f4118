// `objscan render`: Render one depth frame of a scene from a camera pose
// The command line is fixed by DESIGN.md; the work arrives with issue #3.
#include <cstdio>

#include "commands.h"

namespace objscan::app {

void AddRenderCommand(CLI::App& root, RunFn* run) {
  auto* cmd = root.add_subcommand("render", "Render one depth frame of a scene from a camera pose");
  cmd->add_option("--scene", "scene SPEC")->required();
  cmd->add_option("--pose", "camera pose x,y,z,yaw_deg,pitch_deg")->required();
  cmd->add_option("--out", "output folder")->required();
  cmd->callback([run] {
    *run = [] {
      std::fprintf(stderr, "objscan render: not available in this build yet (issue #3)\n");
      return 3;
    };
  });
}

}  // namespace objscan::app
