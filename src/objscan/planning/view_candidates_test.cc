#include "objscan/planning/view_candidates.h"

#include <gtest/gtest.h>

#include <cmath>

namespace objscan::planning {
namespace {

void ExpectLooksAt(const geometry::Pose3& T, const Eigen::Vector3d& target) {
  const Eigen::Vector3d to_target = (target - T.translation()).normalized();
  EXPECT_NEAR(T.linear().col(2).dot(to_target), 1.0, 1e-9);
  EXPECT_NEAR(T.linear().col(0).z(), 0.0, 1e-9);  // image X horizontal
}

TEST(ViewCandidatesTest, SixteenCandidatesAroundTheObjectWithinLimits) {
  const ViewCandidateOptions options;
  const CameraFrustum frustum;
  const Eigen::Vector3d target(1.0, 2.0, 0.5);
  const double radius = 0.6;
  const std::vector<geometry::Pose3> poses = GenerateViewCandidates(target, radius, frustum, options);
  ASSERT_EQ(poses.size(), 16u);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const geometry::Pose3& T = poses[k];
    ExpectLooksAt(T, target);
    const Eigen::Vector3d d = T.translation() - target;
    EXPECT_NEAR(std::atan2(d.y(), d.x()), geometry::WrapAngle(2.0 * M_PI * k / 16.0), 1e-9);  // own azimuth
    EXPECT_GE(T.translation().z(), options.min_camera_height_m - 1e-12);
    EXPECT_LE(T.translation().z(), options.max_camera_height_m + 1e-12);
    double yaw, pitch;
    geometry::YawPitchOfCamera(T, &yaw, &pitch);
    EXPECT_GE(geometry::RadToDeg(pitch), options.min_pitch_deg - 1e-9);
    EXPECT_LE(geometry::RadToDeg(pitch), options.max_pitch_deg + 1e-9);
    // The bounding sphere lies within the valid depth range...
    const double distance = d.norm();
    EXPECT_GE(distance - radius, frustum.min_range_m);
    EXPECT_LE(distance + radius, frustum.max_range_m);
    // ...and within the narrower half field of view.
    EXPECT_LE(std::asin(radius / distance), std::atan(frustum.tan_half_fov_y) + 1e-9);
  }
  // Two rings: even candidates lower than odd ones.
  EXPECT_LT(poses[0].translation().z(), poses[1].translation().z());
}

TEST(ViewCandidatesTest, ArmReachAndPitchLimitsAreRespectedForALowObject) {
  ViewCandidateOptions options;
  options.ring_elevations_deg = {80.0};  // would be almost straight above
  const Eigen::Vector3d target(0.0, 0.0, 0.1);
  const std::vector<geometry::Pose3> poses = GenerateViewCandidates(target, 0.2, CameraFrustum(), options);
  for (const geometry::Pose3& T : poses) {
    ExpectLooksAt(T, target);
    EXPECT_LE(T.translation().z(), options.max_camera_height_m + 1e-12);
    double yaw, pitch;
    geometry::YawPitchOfCamera(T, &yaw, &pitch);
    EXPECT_GE(geometry::RadToDeg(pitch), options.min_pitch_deg - 1e-9);
  }
}

TEST(ViewCandidatesTest, FrustumFromPinholeAndContains) {
  const CameraFrustum f = CameraFrustum::FromPinhole(640, 480, 525.0, 525.0, 0.5, 4.0);
  EXPECT_DOUBLE_EQ(f.tan_half_fov_x, 320.0 / 525.0);
  EXPECT_TRUE(f.Contains({0.0, 0.0, 1.0}));
  EXPECT_FALSE(f.Contains({0.0, 0.0, 0.4}));   // too near
  EXPECT_FALSE(f.Contains({0.0, 0.0, 4.5}));   // too far
  EXPECT_FALSE(f.Contains({0.7, 0.0, 1.0}));   // right of the image
  EXPECT_TRUE(f.Contains({0.6, 0.0, 1.0}));
  EXPECT_FALSE(f.Contains({0.0, -0.5, 1.0}));  // above the image
  EXPECT_FALSE(f.Contains({0.0, 0.0, -1.0}));  // behind
}

}  // namespace
}  // namespace objscan::planning
