#include "objscan/segmentation/slot_split.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

namespace objscan::segmentation {
namespace {

constexpr double kElement = 0.01;  // m, the elements' spacing
constexpr double kElementArea = kElement * kElement;

struct Surface {
  std::vector<Eigen::Vector3f> points, normals;
  // A rectangle of elements spanning [a0, a1] x [b0, b1] along axes u, v at `origin`, facing n.
  void Rect(const Eigen::Vector3f& origin, const Eigen::Vector3f& u, double a0, double a1, const Eigen::Vector3f& v,
            double b0, double b1, const Eigen::Vector3f& n) {
    for (double a = a0; a <= a1 + 1e-9; a += kElement) {
      for (double b = b0; b <= b1 + 1e-9; b += kElement) {
        points.push_back(origin + static_cast<float>(a) * u + static_cast<float>(b) * v);
        normals.push_back(n);
      }
    }
  }
  // What a robot sees of a box against a wall at x = 0 (0.6 deep, front at x = 0.6): its front and
  // top, and its side faces (facing -y at y0, +y at y1) up to `side_depth_m` behind the front.
  void Box(double y0, double y1, double height, double side_depth_m) {
    const Eigen::Vector3f X = Eigen::Vector3f::UnitX(), Y = Eigen::Vector3f::UnitY(), Z = Eigen::Vector3f::UnitZ();
    Rect(Eigen::Vector3f(0.6f, 0.f, 0.f), Y, y0, y1, Z, 0.0, height, X);                            // front
    Rect(Eigen::Vector3f(0.f, 0.f, static_cast<float>(height)), X, 0.0, 0.6, Y, y0, y1, Z);          // top
    Rect(Eigen::Vector3f(0.f, static_cast<float>(y0), 0.f), X, 0.6 - side_depth_m, 0.6, Z, 0.0, height, -Y);
    Rect(Eigen::Vector3f(0.f, static_cast<float>(y1), 0.f), X, 0.6 - side_depth_m, 0.6, Z, 0.0, height, Y);
  }
};

SlotSplitOptions Enabled() {
  SlotSplitOptions o;
  o.enabled = true;
  return o;
}

// Slots found between two 0.6 m boxes `gap_m` apart, their side faces seen `side_depth_m` deep.
std::size_t SlotsBetweenTwoBoxes(double gap_m, double side_depth_m, const SlotSplitOptions& options = Enabled()) {
  Surface s;
  s.Box(0.0, 0.6, 0.9, side_depth_m);
  s.Box(0.6 + gap_m, 1.2 + gap_m, 0.9, side_depth_m);
  return FindSlots(s.points, s.normals, kElementArea, options).size();
}

TEST(FindSlotsTest, CutsBetweenTwoCabinetsStandingAGapApart) {
  Surface s;
  s.Box(0.0, 0.6, 0.9, 0.1);
  s.Box(0.625, 1.225, 0.9, 0.1);
  const std::vector<Slot> slots = FindSlots(s.points, s.normals, kElementArea, Enabled());
  ASSERT_EQ(slots.size(), 1u);
  const Slot& slot = slots[0];
  EXPECT_NEAR(std::fabs(slot.axis.y()), 1.0, 1e-3);
  // The cut lies in the gap, whatever the axis' sign.
  const double gap_centre = 0.6125 * slot.axis.y();
  EXPECT_NEAR(slot.offset_m, gap_centre, 0.015);
  EXPECT_TRUE(slot.Before(Eigen::Vector3f(0.6f, slot.axis.y() > 0 ? 0.3f : 0.9f, 0.5f)));
  EXPECT_FALSE(slot.Before(Eigen::Vector3f(0.6f, slot.axis.y() > 0 ? 0.9f : 0.3f, 0.5f)));
  // The sheets span the side faces seen (between quantiles): x 0.5 to 0.6, z 0 to 0.9.
  EXPECT_NEAR(std::fabs(slot.across_min_m + slot.across_max_m) / 2.0, 0.55, 0.02);
  EXPECT_NEAR(slot.z_min_m, 0.0, 0.06);
  EXPECT_NEAR(slot.z_max_m, 0.9, 0.06);
}

TEST(FindSlotsTest, ThreeCabinetsGiveTwoCuts) {
  Surface s;
  for (int k = 0; k < 3; ++k) s.Box(0.625 * k, 0.625 * k + 0.6, 0.9, 0.1);
  EXPECT_EQ(FindSlots(s.points, s.normals, kElementArea, Enabled()).size(), 2u);
}

TEST(FindSlotsTest, NoCutAcrossADoorGapAFarGapOrBetweenFacesTurnedAway) {
  EXPECT_EQ(SlotsBetweenTwoBoxes(0.025, 0.1), 1u);
  // Door gap: 5 mm, below min_gap_m.
  EXPECT_EQ(SlotsBetweenTwoBoxes(0.005, 0.1), 0u);
  // 30 cm apart: two objects, but no slot (their gap is resolved anyway).
  EXPECT_EQ(SlotsBetweenTwoBoxes(0.3, 0.1), 0u);
  // A panel 3 cm thick: its faces turn away from each other (-y first, then +y).
  Surface panel;
  const Eigen::Vector3f X = Eigen::Vector3f::UnitX(), Y = Eigen::Vector3f::UnitY(), Z = Eigen::Vector3f::UnitZ();
  panel.Rect(Eigen::Vector3f(0.6f, 0.f, 0.f), Y, 0.0, 1.2, Z, 0.0, 0.9, X);
  panel.Rect(Eigen::Vector3f(0.f, 0.6f, 0.f), X, 0.0, 0.6, Z, 0.0, 0.9, -Y);
  panel.Rect(Eigen::Vector3f(0.f, 0.63f, 0.f), X, 0.0, 0.6, Z, 0.0, 0.9, Y);
  EXPECT_TRUE(FindSlots(panel.points, panel.normals, kElementArea, Enabled()).empty());
}

TEST(FindSlotsTest, ChairSeatAndBackrestAFewCentimetresApartAreNoSlot) {
  // The seat's back edge (facing +y, 8 cm tall) 3 cm before the backrest's front (facing -y, from
  // the seat up to 1 m): sheets turned to each other, but at different heights.
  const Eigen::Vector3f X = Eigen::Vector3f::UnitX(), Y = Eigen::Vector3f::UnitY(), Z = Eigen::Vector3f::UnitZ();
  Surface chair;
  chair.Rect(Eigen::Vector3f(0.f, 0.f, 0.45f), X, 0.0, 0.45, Y, 0.0, 0.45, Z);     // seat top
  chair.Rect(Eigen::Vector3f(0.f, 0.f, 0.f), X, 0.0, 0.45, Z, 0.37, 0.45, -Y);      // seat front edge
  chair.Rect(Eigen::Vector3f(0.f, 0.45f, 0.f), X, 0.0, 0.45, Z, 0.37, 0.45, Y);     // seat back edge
  chair.Rect(Eigen::Vector3f(0.f, 0.48f, 0.f), X, 0.0, 0.45, Z, 0.45, 1.0, -Y);     // backrest front
  chair.Rect(Eigen::Vector3f(0.f, 0.51f, 0.f), X, 0.0, 0.45, Z, 0.45, 1.0, Y);      // backrest back
  EXPECT_TRUE(FindSlots(chair.points, chair.normals, kElementArea, Enabled()).empty());
  // Without the overlap rule, they would be one.
  SlotSplitOptions any_overlap = Enabled();
  any_overlap.min_sheet_overlap = 0.0;
  EXPECT_EQ(FindSlots(chair.points, chair.normals, kElementArea, any_overlap).size(), 1u);
}

TEST(FindSlotsTest, SmallSheetsAndSmallPiecesAreNoSlot) {
  // Side faces seen only 1 cm deep: 0.009 m2 each, under min_sheet_area_m2.
  EXPECT_EQ(SlotsBetweenTwoBoxes(0.025, 0.0), 0u);
  // Each box holds about 1.1 m2: under a min_part_area_m2 of 1.2 on either side.
  SlotSplitOptions o = Enabled();
  o.min_part_area_m2 = 1.2;
  EXPECT_EQ(SlotsBetweenTwoBoxes(0.025, 0.1, o), 0u);
}

TEST(FindSlotsTest, RotatedRunIsCutAlongItsOwnAxis) {
  Surface s;
  s.Box(0.0, 0.6, 0.9, 0.1);
  s.Box(0.625, 1.225, 0.9, 0.1);
  const double yaw = 0.5;  // rad
  const Eigen::Matrix3f R = Eigen::AngleAxisf(static_cast<float>(yaw), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  for (auto& p : s.points) p = R * p;
  for (auto& n : s.normals) n = R * n;
  const std::vector<Slot> slots = FindSlots(s.points, s.normals, kElementArea, Enabled());
  ASSERT_EQ(slots.size(), 1u);
  const Eigen::Vector3f run_axis = R * Eigen::Vector3f::UnitY();
  EXPECT_NEAR(std::fabs(slots[0].axis.dot(run_axis)), 1.0, 1e-3);
}

TEST(FindSlotsTest, DisabledFindsNothing) { EXPECT_EQ(SlotsBetweenTwoBoxes(0.025, 0.1, SlotSplitOptions()), 0u); }

}  // namespace
}  // namespace objscan::segmentation
