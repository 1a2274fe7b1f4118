#include "objscan/platform/platform.h"

namespace objscan::platform {

const char* ReachStatusName(ReachStatus status) {
  switch (status) {
    case ReachStatus::kOk: return "ok";
    case ReachStatus::kCameraHeightOutOfRange: return "camera_height_out_of_range";
    case ReachStatus::kPitchOutOfRange: return "pitch_out_of_range";
    case ReachStatus::kNoFreeBase: return "no_free_base";
    case ReachStatus::kStartBlocked: return "start_blocked";
    case ReachStatus::kUnreachable: return "unreachable";
  }
  return "unknown";
}

}  // namespace objscan::platform
