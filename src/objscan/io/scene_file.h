#pragma once
// objscan scene files (.yaml / .yml / .json; JSON is read as YAML). Format:
//
//   name: my_room                  # optional, default: the file name
//   floor: true                    # optional, default true: a floor quad (category floor) at z = 0
//                                  # under the walls (or the objects when there are no walls) plus
//                                  # a 0.5 m margin
//   walls:                         # optional: axis-aligned boxes in the world frame, metres
//     - {min: [-3, -2, 0], max: [3, -1.9, 2.5]}
//   objects:
//     - mesh: models/chair.obj     # a mesh file, relative to this scene file (see mesh_io.h) ...
//       category: chair            # objscan category (Table 2 names), default other
//       pose: [1.0, 0.5, 0, 0, 0, 1.57]   # x y z (m) roll pitch yaw (rad) of the object frame,
//                                          # default all 0
//       scale: 1.0                 # a number or [sx, sy, sz], default 1
//       up_axis: auto              # auto | z | y: axis convention of the mesh file, default auto
//       name: chair_1              # optional, default "<model>_<index>"
//       model: chair_17            # optional source model name, default the mesh file's stem
//     - box: [0.8, 0.6, 0.75]      # ... or a box of this size (m) standing on the object frame's
//       category: table            # origin (its bottom at z = 0)
//       pose: [0, 0, 0, 0, 0, 0]
//
// Unknown keys, unknown categories, missing mesh files and malformed values throw InputError
// naming the file and the element ("room.yaml: objects[2]: unknown key 'rotation'").
#include <string>

#include "objscan/world/scene.h"

namespace objscan::io {

world::Scene LoadSceneFile(const std::string& path);

}  // namespace objscan::io
