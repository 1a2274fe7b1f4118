#include "pose_conversion.h"

#include <gtest/gtest.h>

#include <cmath>

#include "objscan/common/error.h"

namespace objscan::ros_bridge {
namespace {

TEST(PoseConversionTest, CameraPoseRoundTripsToRounding) {
  const geometry::Pose3 T = geometry::CameraPoseFromYawPitch(Eigen::Vector3d(1.5, -2.25, 1.1), 2.3,
                                                             geometry::DegToRad(-35.0));
  const TransformBuffer t = TransformFromPose(T);
  EXPECT_EQ(t.translation_m[0], 1.5);
  EXPECT_EQ(t.translation_m[2], 1.1);
  const double norm = std::sqrt(t.rotation_xyzw[0] * t.rotation_xyzw[0] + t.rotation_xyzw[1] * t.rotation_xyzw[1] +
                                t.rotation_xyzw[2] * t.rotation_xyzw[2] + t.rotation_xyzw[3] * t.rotation_xyzw[3]);
  EXPECT_NEAR(norm, 1.0, 1e-15);
  const geometry::Pose3 back = PoseFromTransform(t, "tf");
  EXPECT_LT((back.matrix() - T.matrix()).norm(), 1e-14);
}

TEST(PoseConversionTest, OpticalFrameLooksAlongZ) {
  // The camera looking along world +X (yaw 0, level): its z axis is world +X, its y axis world -Z.
  const geometry::Pose3 T = geometry::CameraPoseFromYawPitch(Eigen::Vector3d(0, 0, 1), 0.0, 0.0);
  const geometry::Pose3 back = PoseFromTransform(TransformFromPose(T), "tf");
  EXPECT_LT((back.linear().col(2) - Eigen::Vector3d::UnitX()).norm(), 1e-12);
  EXPECT_LT((back.linear().col(1) + Eigen::Vector3d::UnitZ()).norm(), 1e-12);
}

TEST(PoseConversionTest, UnnormalisedQuaternionsAreNormalised) {
  TransformBuffer t;
  t.rotation_xyzw = {0.0, 0.0, 2.0, 2.0};  // 90 degrees about z, length 2.83
  const geometry::Pose3 pose = PoseFromTransform(t, "tf");
  EXPECT_LT((pose.linear().col(0) - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  t.rotation_xyzw = {0.0, 0.0, 0.0, 0.0};
  EXPECT_THROW(PoseFromTransform(t, "tf"), InputError);
  t.rotation_xyzw = {0.0, 0.0, 0.0, 1.0};
  t.translation_m[1] = NAN;
  EXPECT_THROW(PoseFromTransform(t, "tf"), InputError);
}

TEST(PoseConversionTest, BaseRoundTrips) {
  for (double theta : {0.0, 1.0, -2.5, 3.1}) {
    platform::BasePose base;
    base.xy_m = Eigen::Vector2d(2.0, -1.0);
    base.theta_rad = theta;
    const platform::BasePose back = BaseFromTransform(TransformFromBase(base), "tf");
    EXPECT_EQ(back.xy_m, base.xy_m);
    EXPECT_NEAR(back.theta_rad, theta, 1e-12);
  }
}

}  // namespace
}  // namespace objscan::ros_bridge
