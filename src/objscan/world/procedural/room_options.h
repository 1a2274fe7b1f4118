#pragma once
// Options of the procedural room generator.
#include "objscan/common/error.h"

namespace objscan::world::procedural {

struct RoomOptions {
  double wall_thickness_m = 0.1;
  // Free-floor check that every placement must keep true (see floor_check.h).
  double floor_cell_m = 0.05;
  double passage_m = 0.8;
  double max_reach_m = 1.5;
  // Furniture count (every non-structural object, door and windows included).
  int min_objects = 6;
  int max_objects = 20;
  // Whole-room redraws when fewer than min_objects could be placed.
  int max_attempts = 12;

  template <class V>
  void Visit(V& v) {
    v("wall_thickness_m", wall_thickness_m);
    v("floor_cell_m", floor_cell_m);
    v("passage_m", passage_m);
    v("max_reach_m", max_reach_m);
    v("min_objects", min_objects);
    v("max_objects", max_objects);
    v("max_attempts", max_attempts);
  }
  void Validate() const {
    if (!(wall_thickness_m > 0.0 && wall_thickness_m <= 0.5)) throw ConfigError("wall_thickness_m must be in (0, 0.5]");
    if (!(floor_cell_m > 0.0 && floor_cell_m <= 0.2)) throw ConfigError("floor_cell_m must be in (0, 0.2]");
    if (!(passage_m >= 0.0 && passage_m <= 2.0)) throw ConfigError("passage_m must be in [0, 2]");
    if (!(max_reach_m > 0.0)) throw ConfigError("max_reach_m must be > 0");
    if (min_objects < 0 || max_objects < min_objects) throw ConfigError("max_objects must be >= min_objects >= 0");
    if (max_attempts < 1) throw ConfigError("max_attempts must be >= 1");
  }
};

}  // namespace objscan::world::procedural
