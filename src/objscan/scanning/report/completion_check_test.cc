#include "objscan/scanning/report/completion_check.h"

#include <gtest/gtest.h>

#include <cmath>

#include "objscan/recognition/test_shapes.h"

namespace objscan::scanning {
namespace {

std::vector<Eigen::Vector3f> Box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<Eigen::Vector3f> points, normals;
  recognition::testing::BoxSurface(lo, hi, 0.02, &points, &normals);
  return points;
}

TEST(CompletionCheckTest, AWardrobeSeenBeyondTheDoorModelThatCompletedIt) {
  // A door model: a 0.9 x 0.04 x 2.0 m leaf centred on its frame's origin.
  const std::vector<Eigen::Vector3f> door = Box({-0.45, -0.02, 0.0}, {0.45, 0.02, 2.0});
  // Placed turned by 90 degrees about z at (3, 1, 0): the leaf runs along world y, 4 cm thick in x.
  geometry::Pose3 T_world_door = geometry::Pose3::Identity();
  T_world_door.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_world_door.translation() = Eigen::Vector3d(3.0, 1.0, 0.0);
  // The wardrobe's front is the leaf; seen whole, its body runs 0.6 m behind it (+x).
  const std::vector<Eigen::Vector3f> front = Box({2.98, 0.55, 0.0}, {3.02, 1.45, 2.0});
  EXPECT_DOUBLE_EQ(ShareOutsideModelBox(front, door, T_world_door, 0.05), 0.0);
  const std::vector<Eigen::Vector3f> wardrobe = Box({2.98, 0.55, 0.0}, {3.6, 1.45, 2.0});
  const double share = ShareOutsideModelBox(wardrobe, door, T_world_door, 0.05);
  // The points beyond x = 3.02 + 0.05 are outside: most of the top, bottom and sides.
  std::size_t beyond = 0;
  for (const auto& p : wardrobe) beyond += p.x() > 3.07f;
  EXPECT_NEAR(share, static_cast<double>(beyond) / wardrobe.size(), 1e-12);
  EXPECT_GT(share, 0.3);
  // A margin as deep as the body holds it all.
  EXPECT_DOUBLE_EQ(ShareOutsideModelBox(wardrobe, door, T_world_door, 0.6), 0.0);
  // Nothing seen: nothing outside; no model points: everything outside.
  EXPECT_DOUBLE_EQ(ShareOutsideModelBox({}, door, T_world_door, 0.05), 0.0);
  EXPECT_DOUBLE_EQ(ShareOutsideModelBox(front, {}, T_world_door, 0.05), 1.0);
}

TEST(CompletionCheckTest, OptionsAreChecked) {
  CompletionCheckOptions options;
  EXPECT_NO_THROW(options.Validate());
  options.max_outside_share = -1.0;  // off is leaving reopen_outgrown out of report.rules
  EXPECT_THROW(options.Validate(), std::exception);
  options.max_outside_share = 1.5;
  EXPECT_THROW(options.Validate(), std::exception);
  options.max_outside_share = 0.3;
  options.margin_m = -0.1;
  EXPECT_THROW(options.Validate(), std::exception);
}

}  // namespace
}  // namespace objscan::scanning
