#include "objscan/platform/robot_options.h"

namespace objscan::platform {

void RobotOptions::Validate() const {
  config::RequirePositive("base_radius_m", base_radius_m);
  config::RequirePositive("height_m", height_m);
  config::RequireNonNegative("min_camera_height_m", min_camera_height_m);
  config::Require(max_camera_height_m >= min_camera_height_m, "max_camera_height_m", "must be >= min_camera_height_m");
  config::RequireInRange("min_pitch_deg", min_pitch_deg, -89.0, 89.0);
  config::RequireInRange("max_pitch_deg", max_pitch_deg, min_pitch_deg, 89.0);
  config::RequireNonNegative("max_reach_m", max_reach_m);
  config::RequirePositive("speed_m_per_s", speed_m_per_s);
  config::RequirePositive("turn_rate_deg_per_s", turn_rate_deg_per_s);
  config::RequireNonNegative("arm_move_s", arm_move_s);
  config::RequirePositive("base_search_step_m", base_search_step_m);
  config::RequireInRange("base_search_directions", base_search_directions, 1, 3600);
}

}  // namespace objscan::platform
