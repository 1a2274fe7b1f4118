#include "objscan/geometry/pose.h"

#include <gtest/gtest.h>

#include "objscan/geometry/mesh.h"

namespace objscan::geometry {
namespace {

TEST(PoseTest, RpyFollowsSdfConvention) {
  const Pose3 T = PoseFromXyzRpy(1, 2, 3, 0, 0, M_PI / 2);
  const Eigen::Vector3d p = T * Eigen::Vector3d(1, 0, 0);
  EXPECT_NEAR((p - Eigen::Vector3d(1, 3, 3)).norm(), 0.0, 1e-12);
  // Roll about X maps +Y to +Z.
  const Pose3 R = PoseFromXyzRpy(0, 0, 0, M_PI / 2, 0, 0);
  EXPECT_NEAR((R * Eigen::Vector3d(0, 1, 0) - Eigen::Vector3d(0, 0, 1)).norm(), 0.0, 1e-12);
}

TEST(PoseTest, CameraLooksAlongYawPitch) {
  const Pose3 T = CameraPoseFromYawPitch(Eigen::Vector3d(0, 0, 1), M_PI / 2, 0.0);
  EXPECT_NEAR((T.linear().col(2) - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, 1e-12);  // forward +Y
  EXPECT_NEAR(T.linear().col(1).z(), -1.0, 1e-12);                                  // image down is world down
  EXPECT_NEAR(T.linear().determinant(), 1.0, 1e-12);
  double yaw, pitch;
  YawPitchOfCamera(CameraPoseFromYawPitch(Eigen::Vector3d::Zero(), 0.3, -0.4), &yaw, &pitch);
  EXPECT_NEAR(yaw, 0.3, 1e-12);
  EXPECT_NEAR(pitch, -0.4, 1e-12);
  Pose3 L;
  ASSERT_TRUE(CameraPoseLookAt(Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(2, 0, 1), &L));
  EXPECT_NEAR((L.linear().col(2) - Eigen::Vector3d(1, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_FALSE(CameraPoseLookAt(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1, 1, 1), &L));
}

TEST(MeshTest, BoxHasOutwardNormalsAndKnownArea) {
  const TriangleMesh box = MakeBox(Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR(SurfaceArea(box), 2 * (2 + 3 + 6), 1e-6);
  for (const auto& t : box.triangles) {
    const Eigen::Vector3f a = box.vertices[t[0]], b = box.vertices[t[1]], c = box.vertices[t[2]];
    const Eigen::Vector3f n = (b - a).cross(c - a);
    EXPECT_GT(n.dot((a + b + c) / 3.f), 0.f);  // points away from the centre
  }
  const Aabb3 bounds = Bounds(box);
  EXPECT_NEAR((bounds.Size() - Eigen::Vector3d(1, 2, 3)).norm(), 0.0, 1e-6);
}

TEST(MeshTest, CylinderIsClosedWithOutwardNormals) {
  const TriangleMesh c = MakeCylinder(0.5, 2.0, 32);
  for (const auto& t : c.triangles) {
    const Eigen::Vector3f a = c.vertices[t[0]], b = c.vertices[t[1]], d = c.vertices[t[2]];
    EXPECT_GT((b - a).cross(d - a).dot((a + b + d) / 3.f), 0.f);
  }
  // Area close to 2*pi*r*h + 2*pi*r^2 (polygon approximation within 1%).
  EXPECT_NEAR(SurfaceArea(c), 2 * M_PI * 0.5 * 2 + 2 * M_PI * 0.25, 0.01 * (2 * M_PI * 1.25));
}

TEST(MeshTest, DegenerateTrianglesRemoved) {
  TriangleMesh m = MakeQuadXY(0, 0, 1, 1);
  m.triangles.emplace_back(0, 0, 1);
  m.triangles.emplace_back(0, 1, 9);
  EXPECT_EQ(RemoveDegenerateTriangles(&m), 2u);
  EXPECT_EQ(m.triangles.size(), 2u);
}

}  // namespace
}  // namespace objscan::geometry
