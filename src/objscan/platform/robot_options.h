#pragma once
// The robot's body and motion (config section `robot`): a disk-shaped base of base_radius_m, as tall as
// height_m for navigation, carrying the depth camera within the height, pitch and reach limits. The
// method reads the footprint (its navigation map inflates obstacles by it); a platform moves within
// all of it (sim/robot.h: the simulator's arm, speeds and base search).
#include "objscan/common/config.h"

namespace objscan::platform {

struct RobotOptions {
  double base_radius_m = 0.25;
  double height_m = 1.8;             // the body (base and mast) is a cylinder this tall for navigation
  double min_camera_height_m = 0.3;
  double max_camera_height_m = 1.8;
  double min_pitch_deg = -70.0;
  double max_pitch_deg = 30.0;
  double max_reach_m = 0.6;          // camera within this horizontal distance of the base centre
  double speed_m_per_s = 0.3;
  double turn_rate_deg_per_s = 30.0;
  double arm_move_s = 2.0;           // per change of the arm setting
  double base_search_step_m = 0.1;   // candidate base positions: rings this far apart around the camera
  int base_search_directions = 24;   // ... with this many positions per ring

  template <class V>
  void Visit(V& v) {
    v("base_radius_m", base_radius_m);
    v("height_m", height_m);
    v("min_camera_height_m", min_camera_height_m);
    v("max_camera_height_m", max_camera_height_m);
    v("min_pitch_deg", min_pitch_deg);
    v("max_pitch_deg", max_pitch_deg);
    v("max_reach_m", max_reach_m);
    v("speed_m_per_s", speed_m_per_s);
    v("turn_rate_deg_per_s", turn_rate_deg_per_s);
    v("arm_move_s", arm_move_s);
    v("base_search_step_m", base_search_step_m);
    v("base_search_directions", base_search_directions);
  }
  void Validate() const;
};

}  // namespace objscan::platform
