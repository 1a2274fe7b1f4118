#pragma once
// NBV viewpoint candidates V_1..V_{n_v} around the object of interest (§5.2 "Viewpoint candidates"), and
// the seam through which the scanner says which of them the robot can actually use.
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/geometry/pose.h"

namespace objscan::planning {

// What the depth camera sees: a symmetric pinhole frustum and the valid depth range (depth along the
// optical axis, as a depth image stores it).
struct CameraFrustum {
  double tan_half_fov_x = 320.0 / 525.0;  // Kinect: 640 px wide, fx = 525
  double tan_half_fov_y = 240.0 / 525.0;
  double min_range_m = 0.5;
  double max_range_m = 4.0;

  static CameraFrustum FromPinhole(int width_px, int height_px, double fx_px, double fy_px, double min_range_m,
                                   double max_range_m);
  // Point in the camera optical frame (X right, Y down, Z forward) inside the frustum and range.
  bool Contains(const Eigen::Vector3d& p_camera) const {
    const double z = p_camera.z();
    return z >= min_range_m && z <= max_range_m && std::abs(p_camera.x()) <= tan_half_fov_x * z &&
           std::abs(p_camera.y()) <= tan_half_fov_y * z;
  }
};

struct ViewCandidateOptions {
  int num_candidates = 16;  // n_v
  // Elevation of the candidate above the target as seen from the target; candidate k sits on ring
  // k mod (number of rings) at azimuth 2 pi k / n_v, so every candidate has its own azimuth.
  std::vector<double> ring_elevations_deg = {10.0, 30.0};
  // The object's bounding sphere may fill at most this fraction of the narrower half field of view.
  double fov_fill_fraction = 0.85;
  // Candidates come no farther than this from the target (a large object in a small room is then
  // seen in parts rather than from beyond the walls); never closer than the depth range allows.
  double max_distance_m = 2.0;
  double near_radius_cap_m = 0.5;
  double range_margin_m = 0.1;  // keep the object this far inside [min_range, max_range]
  // Reach of the arm holding the camera, and its tilt limits (positive pitch looks up).
  double min_camera_height_m = 0.3;
  double max_camera_height_m = 1.8;
  double min_pitch_deg = -70.0;
  double max_pitch_deg = 30.0;

  template <class V>
  void Visit(V& v) {
    v("num_candidates", num_candidates);
    v("ring_elevations_deg", ring_elevations_deg);
    v("fov_fill_fraction", fov_fill_fraction);
    v("max_distance_m", max_distance_m);
    v("near_radius_cap_m", near_radius_cap_m);
    v("range_margin_m", range_margin_m);
    v("min_camera_height_m", min_camera_height_m);
    v("max_camera_height_m", max_camera_height_m);
    v("min_pitch_deg", min_pitch_deg);
    v("max_pitch_deg", max_pitch_deg);
  }
  void Validate() const;
};

// Camera poses (optical frame, image X horizontal) looking at `target_world`, for an object whose
// bounding sphere around the target has radius `radius_m`. The distance fits the sphere into the field
// of view and the depth range when both are possible (the range wins otherwise); the height is clamped
// to the arm's reach and the horizontal distance widened when the pitch would leave its limits.
std::vector<geometry::Pose3> GenerateViewCandidates(const Eigen::Vector3d& target_world, double radius_m,
                                                    const CameraFrustum& frustum,
                                                    const ViewCandidateOptions& options);

enum class ViewValidity {
  kValid = 0,
  kOccupied,            // camera inside occupied space
  kUnknown,             // camera inside unexplored space
  kUnreachable,         // the robot cannot get the camera there
  kLineOfSightBlocked,  // something between the camera and the object
  kRedundant,           // the object was already viewed from (nearly) here
};
const char* ToString(ViewValidity validity);

// Implemented by the scanner with the occupancy map and the navigator. One call per candidate (n_v per
// NBV), so a virtual call is cheap here.
class ViewValidator {
 public:
  virtual ~ViewValidator() = default;
  virtual ViewValidity Check(const geometry::Pose3& T_world_camera, const Eigen::Vector3d& target_world) const = 0;
};

}  // namespace objscan::planning
