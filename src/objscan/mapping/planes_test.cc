#include "objscan/mapping/planes.h"

#include <gtest/gtest.h>

#include "objscan/mapping/testing/one_wall.h"

namespace objscan::mapping {
namespace {

using testing::OneWall;

TEST(StructureResultTest, RevealFacesInsideTheWallThicknessBelongToTheWall) {
  const StructureResult s = OneWall();
  const Eigen::Vector3d across(0, 1, 0), down(0, 0, -1), facing_room(1, 0, 0);
  // The side and the top of an opening, 5 cm into a 10 cm wall.
  EXPECT_TRUE(s.InWallReveal({-0.05, 1.0, 1.0}, across, 0.3, 0.5));
  EXPECT_TRUE(s.InWallReveal({-0.05, 1.5, 2.0}, down, 0.3, 0.5));
  // A window pane recessed in the opening faces the room: not a reveal.
  EXPECT_FALSE(s.InWallReveal({-0.08, 1.5, 1.0}, facing_room, 0.3, 0.5));
  // In front of the wall (a cabinet side standing against it), too deep, or beyond the span.
  EXPECT_FALSE(s.InWallReveal({0.05, 1.0, 1.0}, across, 0.3, 0.5));
  EXPECT_FALSE(s.InWallReveal({-0.4, 1.0, 1.0}, across, 0.3, 0.5));
  EXPECT_FALSE(s.InWallReveal({-0.05, 4.5, 1.0}, across, 0.3, 0.5));
  // OnStructure is about the plane itself: the reveal point is within 6 cm, not within 4 cm.
  EXPECT_FALSE(s.OnStructure({-0.05, 1.0, 1.0}, 0.04));
  EXPECT_TRUE(s.OnStructure({-0.05, 1.0, 1.0}, 0.06));
  EXPECT_FALSE(StructureResult().InWallReveal({-0.05, 1.0, 1.0}, across, 0.3, 0.5));
}

TEST(StructureResultTest, WallOpeningsAreBehindThePlaneWithinItsExtent) {
  const StructureResult s = OneWall();
  // A pane 6 cm into the wall, and one 25 cm in (a deep reveal).
  EXPECT_TRUE(s.InWallOpening({-0.06, 1.0, 1.2}, 0.02, 0.3));
  EXPECT_TRUE(s.InWallOpening({-0.25, 1.0, 1.2}, 0.02, 0.3));
  // On the plane (within min depth), in front of it, too deep, beyond the span or above the wall.
  EXPECT_FALSE(s.InWallOpening({-0.01, 1.0, 1.2}, 0.02, 0.3));
  EXPECT_FALSE(s.InWallOpening({0.2, 1.0, 1.2}, 0.02, 0.3));
  EXPECT_FALSE(s.InWallOpening({-0.35, 1.0, 1.2}, 0.02, 0.3));
  EXPECT_FALSE(s.InWallOpening({-0.06, 4.2, 1.2}, 0.02, 0.3));
  EXPECT_FALSE(s.InWallOpening({-0.06, 1.0, 2.7}, 0.02, 0.3));
  EXPECT_FALSE(StructureResult().InWallOpening({-0.06, 1.0, 1.2}, 0.02, 0.3));
}

// Points on a grid over the wall (x = 0 plane, y in [0.5, 3.5], z in [0.2, 2.2]) at signed distances
// cycling through `offsets_m`, with normal `n`.
void WallPatch(const std::vector<double>& offsets_m, const Eigen::Vector3f& n, std::vector<Eigen::Vector3f>* points,
               std::vector<Eigen::Vector3f>* normals) {
  std::size_t k = 0;
  for (int i = 0; i <= 30; ++i) {
    for (int j = 0; j <= 20; ++j, ++k) {
      points->emplace_back(static_cast<float>(offsets_m[k % offsets_m.size()]), 0.5f + 0.1f * i, 0.2f + 0.1f * j);
      normals->push_back(n);
    }
  }
}

TEST(StructureResultTest, PlaneNoiseStraddlesTheWallWhereObjectsLieOnOneSide) {
  StructureResult s = OneWall();
  const Eigen::Vector3f facing_room(1, 0, 0), across(0, 1, 0);
  const auto noise = [&](const std::vector<double>& offsets_m, const Eigen::Vector3f& n) {
    std::vector<Eigen::Vector3f> points, normals;
    WallPatch(offsets_m, n, &points, &normals);
    return s.IsPlaneNoise(points, normals, 0.08, 0.2, 0.8);
  };
  // The tail of a wall's depth noise past the 3 cm that tagged it: 4-5 cm on both sides.
  EXPECT_TRUE(noise({-0.045, 0.04, -0.04, 0.05}, facing_room));
  EXPECT_TRUE(noise({-0.045, 0.04, 0.045, 0.05}, facing_room));  // a quarter behind
  // A picture or a window hung 6 cm in front, a door leaf 5 cm into the opening: one side only.
  EXPECT_FALSE(noise({0.06, 0.065, 0.07}, facing_room));
  EXPECT_FALSE(noise({-0.05, -0.055}, facing_room));
  // Faces across the wall (a jamb) are not its surface's noise; beyond the band is not either.
  EXPECT_FALSE(noise({-0.04, 0.04}, across));
  EXPECT_FALSE(noise({-0.12, 0.12}, facing_room));
  // Beyond the wall's span, or no walls at all.
  {
    std::vector<Eigen::Vector3f> points, normals;
    WallPatch({-0.04, 0.04}, facing_room, &points, &normals);
    for (auto& p : points) p.y() += 5.0f;
    EXPECT_FALSE(s.IsPlaneNoise(points, normals, 0.08, 0.2, 0.8));
    EXPECT_FALSE(StructureResult().IsPlaneNoise(points, normals, 0.08, 0.2, 0.8));
  }
  // Band 0 is off; mismatched normals are refused rather than read out of range.
  {
    std::vector<Eigen::Vector3f> points, normals;
    WallPatch({-0.04, 0.04}, facing_room, &points, &normals);
    EXPECT_FALSE(s.IsPlaneNoise(points, normals, 0.0, 0.2, 0.8));
    normals.pop_back();
    EXPECT_FALSE(s.IsPlaneNoise(points, normals, 0.08, 0.2, 0.8));
  }
  // The floor's noise, under and over it; a rug lies on it.
  s.has_floor = true;
  s.floor_height_m = 0.0;
  std::vector<Eigen::Vector3f> floor_noise, rug, up_normals;
  for (int i = 0; i < 40; ++i) {
    floor_noise.emplace_back(1.0f + 0.05f * i, 1.0f, (i % 2 ? 0.04f : -0.04f));
    rug.emplace_back(1.0f + 0.05f * i, 1.0f, 0.03f + 0.001f * (i % 5));
    up_normals.emplace_back(0, 0, 1);
  }
  EXPECT_TRUE(s.IsPlaneNoise(floor_noise, up_normals, 0.08, 0.2, 0.8));
  EXPECT_FALSE(s.IsPlaneNoise(rug, up_normals, 0.08, 0.2, 0.8));
}

}  // namespace
}  // namespace objscan::mapping
