#include "objscan/scanning/report/size_regrouping.h"

#include <cmath>

#include <gtest/gtest.h>

#include "objscan/mapping/planes.h"
#include "objscan/recognition/test_shapes.h"
#include "objscan/scanning/testing/size_fixtures.h"

namespace objscan::scanning {
namespace {

using world::Category;

std::vector<Eigen::Vector3f> Box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<Eigen::Vector3f> points, normals;
  recognition::testing::BoxSurface(lo, hi, 0.02, &points, &normals);
  return points;
}

recognition::CategoryExtents Extents() { return testing::NightStandAndBedSizes(); }
recognition::SizePlausibilityOptions Options() { return testing::TightSizeOptions(); }

TEST(RegroupTest, APieceTooSmallForItsLabelJoinsTheNeighbourItCompletes) {
  // A night stand (0.4 x 0.45 x 0.5 m, diagonal 0.6 m) in two pieces: its body, labelled night
  // stand, and its 0.1 m top slab, labelled bed. A bed stands apart.
  std::vector<RegroupCandidate> objects(3);
  objects[0].points_world = Box({0, 0, 0}, {0.4, 0.45, 0.35});
  objects[0].category = Category::kNightStand;  // 0.35 m tall alone: implausible too (< 0.8 * 0.5)
  objects[1].points_world = Box({0, 0, 0.35}, {0.4, 0.45, 0.5});
  objects[1].category = Category::kBed;
  objects[2].points_world = Box({1, 0, 0}, {3, 1.2, 0.6});
  objects[2].category = Category::kBed;
  const std::vector<std::pair<int, int>> adjacency = {{0, 1}, {1, 2}};
  const RegroupResult r = RegroupImplausibleFragments(objects, adjacency, Extents(), Options());
  // The slab is the smallest implausible object; joined to the bed, the union is no bed (too wide),
  // so it joins the night-stand body, and the union (0.5 m tall) is a night stand.
  EXPECT_EQ(r.merges, 1);
  EXPECT_EQ(r.host, (std::vector<int>{0, 0, 2}));
  ASSERT_TRUE(r.category[0].has_value());
  EXPECT_EQ(*r.category[0], Category::kNightStand);
  EXPECT_EQ(*r.category[2], Category::kBed);
  // The night stand now holds the slab's points; the slab holds none.
  EXPECT_EQ(r.points_world[0].size(), objects[0].points_world.size() + objects[1].points_world.size());
  EXPECT_TRUE(r.points_world[1].empty());
  EXPECT_EQ(r.points_world[2].size(), objects[2].points_world.size());
}

TEST(RegroupTest, AUnionOfTwoImplausiblePiecesTakesTheRecognizedCategoryItFits) {
  // Both halves of a night stand are labelled bed; recognition of the union says bed first (which
  // it does not fit), then night stand.
  std::vector<RegroupCandidate> objects(2);
  objects[0].points_world = Box({0, 0, 0}, {0.4, 0.45, 0.25});
  objects[0].category = Category::kBed;
  objects[1].points_world = Box({0, 0, 0.25}, {0.4, 0.45, 0.5});
  objects[1].category = Category::kBed;
  std::vector<std::vector<int>> asked;
  const auto recognize = [&](const std::vector<int>& members) {
    asked.push_back(members);
    return std::vector<Category>{Category::kBed, Category::kNightStand};
  };
  const RegroupResult r = RegroupImplausibleFragments(objects, {{0, 1}}, Extents(), Options(), recognize);
  EXPECT_EQ(r.merges, 1);
  EXPECT_EQ(r.host[0], r.host[1]);
  const int kept = r.host[0];
  ASSERT_TRUE(r.category[static_cast<std::size_t>(kept)].has_value());
  EXPECT_EQ(*r.category[static_cast<std::size_t>(kept)], Category::kNightStand);
  ASSERT_FALSE(asked.empty());
  EXPECT_EQ(asked.front(), (std::vector<int>{0, 1}));
  // Without recognition, only the labels are candidates and bed does not fit: both stay.
  const RegroupResult alone = RegroupImplausibleFragments(objects, {{0, 1}}, Extents(), Options());
  EXPECT_EQ(alone.merges, 0);
  EXPECT_EQ(alone.host, (std::vector<int>{0, 1}));
}

TEST(RegroupTest, ASmallerPlausibleNeighbourJoinsTheLargerPieceItCompletes) {
  // A bed (2 x 1.2 x 0.6 m) in two pieces: its 0.15 m frame and mattress, labelled bed (too flat for
  // one), and the box under one corner, plausible as the night stand it is labelled. Joined under
  // the night stand's label the union is too large; under the bed's it fits. The box is smaller, so
  // it joins the bed piece, whose record stands for the union.
  std::vector<RegroupCandidate> objects(2);
  objects[0].points_world = Box({0, 0, 0}, {0.4, 0.45, 0.45});
  objects[0].category = Category::kNightStand;
  objects[1].points_world = Box({0, 0, 0.45}, {2, 1.2, 0.6});
  objects[1].category = Category::kBed;
  ASSERT_LT(objects[0].points_world.size(), objects[1].points_world.size());
  const RegroupResult r = RegroupImplausibleFragments(objects, {{0, 1}}, Extents(), Options());
  EXPECT_EQ(r.merges, 1);
  EXPECT_EQ(r.host, (std::vector<int>{1, 1}));
  ASSERT_TRUE(r.category[1].has_value());
  EXPECT_EQ(*r.category[1], Category::kBed);
  EXPECT_EQ(r.points_world[1].size(), objects[0].points_world.size() + objects[1].points_world.size());
  EXPECT_TRUE(r.points_world[0].empty());
  // A neighbour that takes the piece comes first, though smaller: a sparse bed-sized piece labelled
  // bed (eight corner points, plausible) takes the frame; the box stays a night stand.
  objects.resize(3);
  for (double x : {0.0, 2.0})
    for (double y : {0.0, 1.2})
      for (double z : {0.0, 0.5}) objects[2].points_world.emplace_back(x, y, z);
  objects[2].category = Category::kBed;
  const RegroupResult taken = RegroupImplausibleFragments(objects, {{0, 1}, {1, 2}}, Extents(), Options());
  EXPECT_EQ(taken.merges, 1);
  EXPECT_EQ(taken.host, (std::vector<int>{0, 2, 2}));
  EXPECT_EQ(*taken.category[0], Category::kNightStand);
  EXPECT_EQ(*taken.category[2], Category::kBed);
  objects.resize(2);
  // When the union fits neither label, nothing moves.
  objects[1].points_world = Box({0, 0, 0.45}, {3.5, 1.2, 0.6});
  EXPECT_EQ(RegroupImplausibleFragments(objects, {{0, 1}}, Extents(), Options()).merges, 0);
}

TEST(RegroupTest, WhenTheUnionFitsBothLabelsTheLargerPieceNamesIt) {
  // A table top seen without its underside (1 x 0.8 m, 4 cm thick, 0.72 m up: too flat for a table)
  // over its pedestal, labelled sink and plausible as one. The union fits a sink too, but the top
  // holds more points: the pedestal joins the top and the union is a table.
  recognition::CategoryExtents extents;
  extents.Add(Category::kTable, {0.75, 1.4});
  extents.Add(Category::kSink, {0.85, 1.0});
  recognition::SizePlausibilityOptions options;
  options.min_ratio = 0.5;
  options.max_ratio = 1.4;
  std::vector<RegroupCandidate> objects(2);
  objects[0].points_world = Box({0, 0, 0.72}, {1.0, 0.8, 0.76});
  objects[0].category = Category::kTable;
  // The pedestal, seen from fewer views than the top: every other point.
  const std::vector<Eigen::Vector3f> pedestal = Box({0.3, 0.2, 0}, {0.7, 0.6, 0.62});
  for (std::size_t i = 0; i < pedestal.size(); i += 2) objects[1].points_world.push_back(pedestal[i]);
  objects[1].category = Category::kSink;
  ASSERT_GT(objects[0].points_world.size(), objects[1].points_world.size());
  std::vector<Eigen::Vector3f> both = objects[0].points_world;
  both.insert(both.end(), objects[1].points_world.begin(), objects[1].points_world.end());
  const auto plausible = [&](const std::vector<Eigen::Vector3f>& points, Category c) {
    return recognition::IsPlausibleExtent(recognition::MeasureExtent(points), extents.Find(c), options);
  };
  ASSERT_FALSE(plausible(objects[0].points_world, Category::kTable));
  ASSERT_TRUE(plausible(objects[1].points_world, Category::kSink));
  ASSERT_TRUE(plausible(both, Category::kSink));
  ASSERT_TRUE(plausible(both, Category::kTable));
  const RegroupResult r = RegroupImplausibleFragments(objects, {{0, 1}}, extents, options);
  EXPECT_EQ(r.merges, 1);
  EXPECT_EQ(r.host, (std::vector<int>{0, 0}));
  ASSERT_TRUE(r.category[0].has_value());
  EXPECT_EQ(*r.category[0], Category::kTable);
  EXPECT_EQ(r.points_world[0].size(), both.size());
  // The same top over a larger labelled box: that box's label names the union.
  objects[1].points_world = Box({0, 0, 0}, {1.0, 0.8, 0.62});
  ASSERT_GT(objects[1].points_world.size(), objects[0].points_world.size());
  const RegroupResult larger = RegroupImplausibleFragments(objects, {{0, 1}}, extents, options);
  EXPECT_EQ(larger.host, (std::vector<int>{1, 1}));
  EXPECT_EQ(*larger.category[1], Category::kSink);
}

TEST(RegroupTest, PlausibleFixedUnrecognizedAndApartObjectsStay) {
  std::vector<RegroupCandidate> objects(4);
  objects[0].points_world = Box({0, 0, 0}, {0.4, 0.45, 0.5});  // a whole night stand
  objects[0].category = Category::kNightStand;
  objects[1].points_world = Box({0, 0, 0.5}, {0.4, 0.45, 0.6});  // a slab labelled bed ...
  objects[1].category = Category::kBed;
  objects[2].points_world = Box({0.4, 0, 0}, {0.5, 0.45, 0.5});  // unrecognized
  objects[3].points_world = Box({5, 5, 0}, {5.4, 5.45, 0.1});    // a slab far away, adjacent to nothing
  objects[3].category = Category::kBed;
  // The slab and the night stand together are 0.6 m tall: no night stand under a 1.1 ratio (0.55 m).
  recognition::SizePlausibilityOptions options = Options();
  options.max_ratio = 1.1;
  const RegroupResult r = RegroupImplausibleFragments(objects, {{0, 1}, {0, 2}, {1, 2}}, Extents(), options);
  EXPECT_EQ(r.merges, 0);
  EXPECT_EQ(r.host, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_FALSE(r.category[2].has_value());
  // Under 1.3 (0.65 m) the slab joins the night stand, unless it is fixed (completed): then it never
  // hosts.
  objects[0].fixed = true;
  options.max_ratio = 1.3;
  EXPECT_EQ(RegroupImplausibleFragments(objects, {{0, 1}}, Extents(), options).merges, 0);
  objects[0].fixed = false;
  EXPECT_EQ(RegroupImplausibleFragments(objects, {{0, 1}}, Extents(), options).merges, 1);
}

TEST(ObjectsWithinDistanceTest, PairsOfObjectsWithClosePoints) {
  const std::vector<std::vector<Eigen::Vector3f>> points = {
      {{0.f, 0.f, 0.f}, {0.2f, 0.f, 0.f}},
      {{0.23f, 0.f, 0.f}},   // 3 cm from object 0
      {{1.0f, 0.f, 0.f}},    // far from both
      {{0.21f, 0.01f, 0.f}}};
  const auto pairs = ObjectsWithinDistance(points, 0.05);
  EXPECT_EQ(pairs, (std::vector<std::pair<int, int>>{{0, 1}, {0, 3}, {1, 3}}));
}


TEST(ObjectsStandingUnderTest, APedestalUnderATableTopAcrossTheUnseenUnderside) {
  const std::vector<std::vector<Eigen::Vector3f>> points = {
      Box({0, 0, 0.72}, {1.0, 0.8, 0.76}),        // 0: a table top
      Box({0.3, 0.2, 0}, {0.7, 0.6, 0.62}),       // 1: its pedestal, 10 cm below
      Box({1.5, 0, 0}, {2.0, 0.5, 0.62}),         // 2: beside the table, not under it
      Box({-0.5, -0.5, 0}, {1.5, 1.3, 0.3}),      // 3: under it but wider than the top
      Box({0.1, 0.1, 0.77}, {0.3, 0.3, 0.9}),     // 4: a radio on the top: above it, not under
      {}};                                         // 5: absorbed, no points
  EXPECT_EQ(ObjectsStandingUnder(points, 0.15, 0.05), (std::vector<std::pair<int, int>>{{0, 1}}));
  // A gap larger than allowed: apart.
  EXPECT_TRUE(ObjectsStandingUnder(points, 0.05, 0.05).empty());
}

TEST(JoinStackedPiecesTest, AShadeTakenForARadioJoinsTheLampStandingUnderIt) {
  recognition::CategoryExtents extents = Extents();
  extents.Add(Category::kLamp, {1.4, 0.4});
  extents.Add(Category::kLamp, {1.7, 0.5});
  extents.Add(Category::kRadio, {0.2, 0.4});
  extents.Add(Category::kRadio, {0.3, 0.6});
  std::vector<RegroupCandidate> objects(10);
  const auto put = [&](int i, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::optional<Category> c) {
    objects[static_cast<std::size_t>(i)].points_world = Box(lo, hi);
    objects[static_cast<std::size_t>(i)].category = c;
  };
  // A lamp: stem and base labelled lamp (the larger piece), its shade 5 cm above labelled radio.
  put(0, {0.05, 0.05, 0}, {0.35, 0.35, 1.2}, Category::kLamp);
  put(1, {0, 0, 1.25}, {0.4, 0.4, 1.5}, Category::kRadio);
  // A radio on a night stand: it stands on it, not over it; both stay.
  put(2, {1, 0, 0}, {1.4, 0.45, 0.5}, Category::kNightStand);
  put(3, {1.1, 0.1, 0.5}, {1.3, 0.3, 0.7}, Category::kRadio);
  // The same stack with a door label below: doors never join.
  put(4, {3.05, 0.05, 0}, {3.35, 0.35, 1.2}, Category::kDoor);
  put(5, {3, 0, 1.25}, {3.4, 0.4, 1.5}, Category::kRadio);
  // The same stack with the stem replaced by its model (fixed): it stays.
  put(6, {4.05, 0.05, 0}, {4.35, 0.35, 1.2}, Category::kLamp);
  objects[6].fixed = true;
  put(7, {4, 0, 1.25}, {4.4, 0.4, 1.5}, Category::kRadio);
  // A thin stem (fewer points) under a shade labelled radio: the union, 1.5 m tall, is no radio.
  put(8, {5.15, 0.15, 0}, {5.25, 0.25, 1.2}, Category::kLamp);
  put(9, {5, 0, 1.25}, {5.4, 0.4, 1.5}, Category::kRadio);
  ASSERT_GT(objects[0].points_world.size(), objects[1].points_world.size());
  ASSERT_LT(objects[8].points_world.size(), objects[9].points_world.size());
  const RegroupResult r = JoinStackedPieces(objects, 0.15, 0.05, extents, Options());
  EXPECT_EQ(r.merges, 1);
  EXPECT_EQ(r.host, (std::vector<int>{0, 0, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(r.category[0], Category::kLamp);
  EXPECT_EQ(r.points_world[0].size(), objects[0].points_world.size() + objects[1].points_world.size());
  EXPECT_TRUE(r.points_world[1].empty());
}

TEST(JoinStackedPiecesTest, APieceThatTookAnotherHandsItOnWhenItJoins) {
  // Three stacked pieces: a small base (1) under a stem (0) under a large shade (2). Joined in pair
  // order, the base joins the stem, then the stem joins the shade: the base's host is the shade.
  recognition::CategoryExtents extents;
  extents.Add(Category::kLamp, {0.5, 0.3});
  extents.Add(Category::kLamp, {2.0, 1.0});
  std::vector<RegroupCandidate> objects(3);
  objects[0].points_world = Box({0.1, 0.1, 0.2}, {0.3, 0.3, 1.0});  // stem, 0.8 m
  objects[0].category = Category::kRadio;
  objects[1].points_world = Box({0.15, 0.15, 0.0}, {0.25, 0.25, 0.15});  // base
  objects[1].category = Category::kChair;
  objects[2].points_world = Box({-0.1, -0.1, 1.05}, {0.5, 0.5, 1.6});  // shade, 0.6 m wide
  objects[2].category = Category::kLamp;
  ASSERT_GT(objects[0].points_world.size(), objects[1].points_world.size());
  ASSERT_GT(objects[2].points_world.size(), objects[0].points_world.size());
  const std::vector<std::vector<Eigen::Vector3f>> points = {objects[0].points_world, objects[1].points_world,
                                                            objects[2].points_world};
  ASSERT_EQ(ObjectsStandingUnder(points, 0.15, 0.05), (std::vector<std::pair<int, int>>{{0, 1}, {0, 2}}));
  recognition::CategoryExtents all = extents;
  all.Add(Category::kRadio, {0.1, 0.1});
  all.Add(Category::kRadio, {1.0, 0.5});
  const RegroupResult r = JoinStackedPieces(objects, 0.15, 0.05, all, Options());
  EXPECT_EQ(r.merges, 2);
  EXPECT_EQ(r.host, (std::vector<int>{2, 2, 2}));
  EXPECT_EQ(r.points_world[2].size(),
            objects[0].points_world.size() + objects[1].points_world.size() + objects[2].points_world.size());
}

TEST(PointsAwayFromWallsTest, StrayWallReturnsLeaveACabinetsExtentButADoorKeepsItsPoints) {
  // A wall x = 0 facing +x, 5 m long. A cabinet stands against it (x 0.02-0.6 m, y 2-3 m, 0.9 m
  // tall); a line of noisy wall returns 4 cm off the plane joined it, from one end of the wall to
  // the other and up to 2.5 m.
  mapping::StructureResult structure;
  mapping::WallPlane wall;
  wall.normal = Eigen::Vector3d::UnitX();
  wall.offset_m = 0.0;
  wall.span_min_m = 0.0;  // Along = y for this normal
  wall.span_max_m = 5.0;
  wall.z_min_m = 0.0;
  wall.z_max_m = 2.5;
  structure.walls.push_back(wall);
  std::vector<Eigen::Vector3f> cabinet = Box({0.02, 2.0, 0.0}, {0.6, 3.0, 0.9});
  const std::size_t n_cabinet = cabinet.size();
  for (int i = 0; i <= 100; ++i) {
    cabinet.emplace_back(0.04f, 0.05f * static_cast<float>(i), 0.025f * static_cast<float>(i));
  }
  const recognition::ObjectExtent whole = recognition::MeasureExtent(cabinet);
  EXPECT_NEAR(whole.height_m, 2.5, 1e-5);
  EXPECT_GT(whole.footprint_diagonal_m, 4.9);
  const std::vector<Eigen::Vector3f> away = PointsAwayFromWalls(cabinet, structure, 0.08);
  EXPECT_LT(away.size(), n_cabinet);  // the stray line and the cabinet's rear strip are left out
  EXPECT_GT(2 * away.size(), cabinet.size());
  for (const auto& p : away) EXPECT_GE(p.x(), 0.08f);
  const recognition::ObjectExtent e = recognition::MeasureExtent(away);
  EXPECT_NEAR(e.height_m, 0.9, 1e-5);
  EXPECT_NEAR(e.footprint_diagonal_m, std::hypot(0.52, 1.0), 0.03);
  // Beyond the wall's span, nothing is near it.
  EXPECT_EQ(PointsAwayFromWalls(Box({0.0, 6.0, 0.0}, {0.5, 6.5, 0.5}), structure, 0.08).size(),
            Box({0.0, 6.0, 0.0}, {0.5, 6.5, 0.5}).size());
  // A door leaf in the wall's plane: nearly all its points are near the wall, so all stay.
  const std::vector<Eigen::Vector3f> door = Box({-0.04, 1.0, 0.0}, {0.0, 1.9, 2.0});
  EXPECT_EQ(PointsAwayFromWalls(door, structure, 0.08).size(), door.size());
  // Off (margin 0) or no walls: all stay.
  EXPECT_EQ(PointsAwayFromWalls(cabinet, structure, 0.0).size(), cabinet.size());
  EXPECT_EQ(PointsAwayFromWalls(cabinet, mapping::StructureResult(), 0.08).size(), cabinet.size());
}

}  // namespace
}  // namespace objscan::scanning
