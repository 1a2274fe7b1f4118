#pragma once
// Test fixture (header only, not part of the library): a structure result with one known wall, for
// tests of what lies in front of, on or behind a wall plane.
#include <Eigen/Core>

#include "objscan/mapping/planes.h"

namespace objscan::mapping::testing {

// One wall: the plane x = 0 facing +x (the room), spanning y in [0, 4] and z in [0, 2.5]; no floor.
inline StructureResult OneWall() {
  StructureResult s;
  WallPlane w;
  w.normal = Eigen::Vector3d::UnitX();
  w.offset_m = 0.0;
  w.z_min_m = 0.0;
  w.z_max_m = 2.5;
  // Along = -n.y x + n.x y = y.
  w.span_min_m = 0.0;
  w.span_max_m = 4.0;
  s.walls.push_back(w);
  return s;
}

}  // namespace objscan::mapping::testing
