#include "objscan/scanning/coverage_views.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "objscan/common/error.h"

namespace objscan::scanning {
namespace {

TEST(CoverageViewsTest, SurfaceUnderTheFloorClearanceIsLeftOut) {
  const std::vector<Eigen::Vector3f> model = {
      {0.0f, 0.0f, 0.10f}, {0.0f, 0.0f, 0.12f}, {0.0f, 0.0f, 0.1299f}, {0.0f, 0.0f, 0.1301f}, {0.0f, 0.0f, 0.9f}};
  // Floor at 0.1 m, clearance 0.03 m: from 0.13 m up.
  const auto kept = ModelSurfaceAboveFloor(model, true, 0.1, 0.03);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_FLOAT_EQ(kept[0].z(), 0.1301f);
  EXPECT_FLOAT_EQ(kept[1].z(), 0.9f);
  // Without a detected floor the clearance is measured from z = 0: everything here is above 0.03 m.
  EXPECT_EQ(ModelSurfaceAboveFloor(model, false, 0.1, 0.03).size(), model.size());
  EXPECT_TRUE(ModelSurfaceAboveFloor({}, true, 0.0, 0.03).empty());
}

TEST(CoverageViewsTest, UnseenModelPointsAreThoseWithNoSeenPointNearby) {
  // A model row along x every 1 cm from 0 to 1 m; the robot saw the row from 0 to 0.5 m.
  std::vector<Eigen::Vector3f> model, seen;
  for (int i = 0; i <= 100; ++i) model.emplace_back(0.01f * static_cast<float>(i), 0.0f, 0.5f);
  for (int i = 0; i <= 50; ++i) seen.emplace_back(0.01f * static_cast<float>(i), 0.0f, 0.5f);
  const float r = 0.05f;
  const auto unseen = UnseenModelPoints(model, seen, r);
  ASSERT_FALSE(unseen.empty());
  // Every point within r of a seen one is seen; none beyond 2 sqrt(3) r is.
  for (const auto& p : unseen) EXPECT_GT(p.x(), 0.5f + r - 1e-4f);
  for (const auto& p : model) {
    if (p.x() > 0.5f + 2.0f * std::sqrt(3.0f) * r) {
      EXPECT_NE(std::find(unseen.begin(), unseen.end(), p), unseen.end()) << p.x();
    }
  }
  // Nothing seen: all unseen; everything seen: none.
  EXPECT_EQ(UnseenModelPoints(model, {}, r).size(), model.size());
  EXPECT_TRUE(UnseenModelPoints(model, model, r).empty());
}

TEST(CoverageViewsTest, BadOptionsNameTheirField) {
  const auto message = [](const CoverageViewOptions& o) {
    try {
      o.Validate();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(CoverageViewOptions()), "");
  CoverageViewOptions o;
  o.max_views_per_object = -1;
  EXPECT_NE(message(o).find("scanner.coverage_views.max_views_per_object"), std::string::npos);
  o = CoverageViewOptions();
  o.min_unseen_voxels = 0;
  EXPECT_NE(message(o).find("scanner.coverage_views.min_unseen_voxels"), std::string::npos);
  o = CoverageViewOptions();
  o.min_objectness = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(o).find("scanner.coverage_views.min_objectness"), std::string::npos);
  o = CoverageViewOptions();
  o.floor_clearance_m = -0.01;
  EXPECT_NE(message(o).find("scanner.coverage_views.floor_clearance_m"), std::string::npos);
  o = CoverageViewOptions();
  o.ring_elevations_deg = {};
  EXPECT_NE(message(o).find("scanner.coverage_views.ring_elevations_deg"), std::string::npos);
  o.ring_elevations_deg = {-90.0};
  EXPECT_NE(message(o).find("scanner.coverage_views.ring_elevations_deg"), std::string::npos);
}

}  // namespace
}  // namespace objscan::scanning
