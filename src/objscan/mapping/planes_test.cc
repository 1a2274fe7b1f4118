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

}  // namespace
}  // namespace objscan::mapping
