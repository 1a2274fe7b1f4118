#include "objscan/scanning/report/wall_openings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "objscan/mapping/planes.h"
#include "objscan/scanning/testing/wall_shapes.h"

namespace objscan::scanning {
namespace {

using testing::Append;
using testing::OneWallRoom;
using testing::Pane;
using testing::Pleats;

TEST(WallOpeningTest, ARecessedPaneOffTheFloorIsAWindow) {
  const mapping::StructureResult room = OneWallRoom();
  const WallOpeningOptions options;
  // A pane 6 cm behind the wall plane, its sill at 0.9 m.
  const WallOpeningResult r = ClassifyWallOpening(Pane(-0.06, 1.0, 2.0, 0.9, 2.0), room, false, options);
  EXPECT_NEAR(r.share, 1.0, 1e-9);
  EXPECT_EQ(r.verdict, WallOpeningVerdict::kWindow);
  // Already labelled window: still in an opening.
  EXPECT_EQ(ClassifyWallOpening(Pane(-0.06, 1.0, 2.0, 0.9, 2.0), room, true, options).verdict,
            WallOpeningVerdict::kWindow);
}

TEST(WallOpeningTest, WallStripsAroundTheOpeningDoNotHideIt) {
  const mapping::StructureResult room = OneWallRoom();
  WallOpeningOptions options;
  // The pane and a strip of wall beside it down to the floor (on the plane, untagged): the strip is
  // a third of the points, and a few of them reach the floor.
  std::vector<Eigen::Vector3f> points = Pane(-0.06, 1.0, 2.0, 0.9, 2.0);
  const std::size_t pane = points.size();
  Append(Pane(0.0, 2.02, 2.2, 0.9, 2.0), &points);
  Append(Pane(0.0, 2.02, 2.04, 0.0, 0.88), &points);
  const WallOpeningResult r = ClassifyWallOpening(points, room, false, options);
  EXPECT_NEAR(r.share, static_cast<double>(pane) / points.size(), 1e-9);
  EXPECT_GT(r.share, 0.5);
  EXPECT_EQ(r.verdict, WallOpeningVerdict::kWindow);
  // With the bar raised above that share, it stays as it is.
  options.window_min_share = 0.95;
  EXPECT_EQ(ClassifyWallOpening(points, room, false, options).verdict, WallOpeningVerdict::kNoChange);
}

TEST(WallOpeningTest, ThingsInTheRoomAreNotWindows) {
  const mapping::StructureResult room = OneWallRoom();
  const WallOpeningOptions options;
  // A cabinet front 40 cm in front of the wall: no window, and a window label on it goes; so does
  // one on a cabinet front standing on the floor 5 cm from the wall.
  EXPECT_EQ(ClassifyWallOpening(Pane(0.4, 1.0, 2.0, 0.0, 0.9), room, false, options).verdict,
            WallOpeningVerdict::kNoChange);
  EXPECT_EQ(ClassifyWallOpening(Pane(0.4, 1.0, 2.0, 0.0, 0.9), room, true, options).verdict,
            WallOpeningVerdict::kNotWindow);
  const WallOpeningResult front = ClassifyWallOpening(Pane(0.05, 1.0, 1.6, 0.0, 0.9), room, true, options);
  EXPECT_EQ(front.share, 0.0);
  EXPECT_EQ(front.verdict, WallOpeningVerdict::kNotWindow);
  // A pane hanging 40 cm in front of the wall, off the floor: too far from it to be mounted on it.
  EXPECT_EQ(ClassifyWallOpening(Pane(0.4, 1.0, 1.6, 0.8, 1.2), room, true, options).verdict,
            WallOpeningVerdict::kNotWindow);
}

// An opening down to the floor is a doorway: a window label on what lies in it (a door's frame and
// reveals) goes, while the same object off the floor keeps it; with doorways_are_not_windows off,
// the sill only decides which objects are made windows.
TEST(WallOpeningTest, AWindowLabelInAnOpeningDownToTheFloorGoes) {
  const mapping::StructureResult room = OneWallRoom();
  WallOpeningOptions options;
  // A reveal 6 cm behind the wall plane from the floor to 2 m, and twice as many points of wall beside it.
  std::vector<Eigen::Vector3f> doorway = Pane(-0.06, 1.0, 1.2, 0.0, 2.0);
  Append(Pane(0.0, 1.22, 1.62, 0.0, 2.0), &doorway);
  const WallOpeningResult r = ClassifyWallOpening(doorway, room, true, options);
  EXPECT_GT(r.share, options.window_keep_share);
  EXPECT_LT(r.share, options.window_min_share);
  EXPECT_EQ(r.verdict, WallOpeningVerdict::kNotWindow);
  // Nothing is made of it when recognition did not call it a window.
  EXPECT_EQ(ClassifyWallOpening(doorway, room, false, options).verdict, WallOpeningVerdict::kNoChange);
  // The same reveal and wall from a 0.9 m sill up: a window's, the label stays.
  std::vector<Eigen::Vector3f> window = Pane(-0.06, 1.0, 1.2, 0.9, 2.0);
  Append(Pane(0.0, 1.22, 1.62, 0.9, 2.0), &window);
  EXPECT_EQ(ClassifyWallOpening(window, room, true, options).verdict, WallOpeningVerdict::kNoChange);
  options.doorways_are_not_windows = false;
  EXPECT_EQ(ClassifyWallOpening(doorway, room, true, options).verdict, WallOpeningVerdict::kNoChange);
}

// A window mounted on the wall's face (SUNCG rooms: no opening behind it) keeps its label: off the
// floor, within hanging_window_max_distance_m in front of the wall. It is not made a window when
// recognition did not call it one.
TEST(WallOpeningTest, AWindowOnTheWallsFaceKeepsItsLabel) {
  const mapping::StructureResult room = OneWallRoom();
  WallOpeningOptions options;
  std::vector<Eigen::Vector3f> window = Pane(0.03, 1.0, 3.0, 0.85, 2.25);  // the glass
  Append(Pane(0.15, 1.0, 3.0, 0.85, 0.87), &window);                        // the sill, 15 cm out
  const WallOpeningResult kept = ClassifyWallOpening(window, room, true, options);
  EXPECT_EQ(kept.share, 0.0);
  EXPECT_EQ(kept.verdict, WallOpeningVerdict::kNoChange);
  EXPECT_EQ(ClassifyWallOpening(window, room, false, options).verdict, WallOpeningVerdict::kNoChange);
  // Only openings count when the rule is off, and then the label goes.
  options.hanging_window_max_distance_m = -1.0;
  EXPECT_EQ(ClassifyWallOpening(window, room, true, options).verdict, WallOpeningVerdict::kNotWindow);
  // With it on, a share of points away from the wall below hanging_window_min_share loses it too.
  options = WallOpeningOptions();
  Append(Pane(0.6, 1.0, 3.0, 0.85, 1.6), &window);  // as many points again, 60 cm out
  EXPECT_EQ(ClassifyWallOpening(window, room, true, options).verdict, WallOpeningVerdict::kNotWindow);
  options.hanging_window_min_share = 0.3;
  EXPECT_EQ(ClassifyWallOpening(window, room, true, options).verdict, WallOpeningVerdict::kNoChange);
}

// A curtain hanging in front of the wall keeps a window label by the rule above; it may still be
// found to be the curtain over a window in an opening, as unlabelled objects and doors may. A window
// in an opening, and furniture, may not.
TEST(WallOpeningTest, WindowsHangingOnTheWallMayBeCurtains) {
  const WallOpeningOptions options;
  EXPECT_TRUE(MayBeCurtain(std::nullopt, 0.0, options));
  EXPECT_TRUE(MayBeCurtain(world::Category::kDoor, 0.0, options));
  EXPECT_TRUE(MayBeCurtain(world::Category::kCurtain, 0.0, options));
  EXPECT_TRUE(MayBeCurtain(world::Category::kWindow, 0.0, options));
  EXPECT_FALSE(MayBeCurtain(world::Category::kWindow, options.window_keep_share, options));
  EXPECT_FALSE(MayBeCurtain(world::Category::kWindow, 0.6, options));
  EXPECT_FALSE(MayBeCurtain(world::Category::kDresser, 0.0, options));
}

TEST(WallOpeningTest, AnOpeningThatReachesTheFloorIsNoWindow) {
  const mapping::StructureResult room = OneWallRoom();
  const WallOpeningOptions options;
  // A recessed door leaf: in the opening, but from the floor up.
  EXPECT_EQ(ClassifyWallOpening(Pane(-0.05, 1.0, 1.9, 0.0, 2.0), room, false, options).verdict,
            WallOpeningVerdict::kNoChange);
}

TEST(WallOpeningTest, WithoutWallsOrPointsNothingChanges) {
  const std::vector<Eigen::Vector3f> pane = Pane(-0.06, 1.0, 2.0, 0.9, 2.0);
  EXPECT_EQ(ClassifyWallOpening(pane, mapping::StructureResult(), true, WallOpeningOptions()).verdict,
            WallOpeningVerdict::kNoChange);
  EXPECT_EQ(ClassifyWallOpening({}, OneWallRoom(), true, WallOpeningOptions()).verdict, WallOpeningVerdict::kNoChange);
}

TEST(WallOpeningTest, OptionsAreChecked) {
  WallOpeningOptions o;
  o.max_depth_m = 0.01;
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.window_keep_share = 0.8;
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.window_min_share = 1.5;
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.hanging_window_max_distance_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.hanging_window_min_share = 1.5;
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.join_gap_m = -0.1;
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.curtain_max_distance_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.curtain_min_share = -0.1;
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.curtain_max_fold_depth_m = 0.01;
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.curtain_min_fold_depth_m = -0.1;
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.curtain_min_overlap_m = -0.1;
  EXPECT_ANY_THROW(o.Validate());
  o = WallOpeningOptions();
  o.door_max_depth_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_ANY_THROW(o.Validate());
  o.door_max_depth_m = -1.0;
  EXPECT_ANY_THROW(o.Validate());
  EXPECT_NO_THROW(WallOpeningOptions().Validate());
}

TEST(WindowPiecesTest, OpeningBoundsHoldOnlyThePointsInOpenings) {
  // A recessed pane and, in the room, a strip of the object 0.5 m in front of the wall.
  std::vector<Eigen::Vector3f> points = Pane(-0.06, 1.0, 2.0, 0.9, 2.0);
  Append(Pane(0.5, 0.0, 3.0, 0.5, 0.6), &points);
  const OpeningExtent extent = OpeningBounds(points, OneWallRoom(), WallOpeningOptions());
  EXPECT_EQ(extent.wall, 0);
  ASSERT_FALSE(extent.bounds.Empty());
  EXPECT_NEAR(extent.bounds.min_m.x(), -0.06, 1e-6);
  EXPECT_NEAR(extent.bounds.max_m.x(), -0.06, 1e-6);
  EXPECT_NEAR(extent.bounds.min_m.y(), 1.0, 1e-6);
  EXPECT_NEAR(extent.bounds.max_m.y(), 2.0, 1e-6);
  EXPECT_NEAR(extent.bounds.min_m.z(), 0.9, 1e-6);
  EXPECT_NEAR(extent.bounds.max_m.z(), 2.0, 1e-6);
  EXPECT_EQ(OpeningBounds(Pane(0.5, 0.0, 3.0, 0.5, 0.6), OneWallRoom(), WallOpeningOptions()).wall, -1);
  EXPECT_EQ(OpeningBounds(points, mapping::StructureResult(), WallOpeningOptions()).wall, -1);
}

TEST(WindowPiecesTest, OpeningBoundsKeepToTheWallHoldingMostPoints) {
  // A second wall y = 0 facing +y: a window in it near the corner, and a few points of the object
  // behind the first wall.
  mapping::StructureResult room = OneWallRoom();
  mapping::WallPlane second = room.walls.front();
  second.normal = Eigen::Vector3d::UnitY();
  second.offset_m = 0.0;
  second.span_min_m = -4.0;  // Along = -x
  second.span_max_m = 0.0;
  room.walls.push_back(second);
  std::vector<Eigen::Vector3f> points;
  for (double x = 0.2; x <= 1.2 + 1e-9; x += 0.02) {
    for (double z = 1.0; z <= 2.0 + 1e-9; z += 0.02) points.emplace_back(x, -0.06, z);
  }
  Append(Pane(-0.06, 0.5, 0.52, 1.0, 1.1), &points);
  const OpeningExtent extent = OpeningBounds(points, room, WallOpeningOptions());
  EXPECT_EQ(extent.wall, 1);
  EXPECT_NEAR(extent.bounds.min_m.x(), 0.2, 1e-6);
  EXPECT_NEAR(extent.bounds.max_m.y(), -0.06, 1e-6);
}

WindowPiece Piece(double y0, double y1, double z0, double z1, bool window, std::size_t num_points,
                  bool complete = false, int wall = 0) {
  WindowPiece p;
  p.opening.wall = wall;
  p.opening.bounds.Extend(Eigen::Vector3d(-0.1, y0, z0));
  p.opening.bounds.Extend(Eigen::Vector3d(-0.05, y1, z1));
  p.window = window;
  p.complete = complete;
  p.num_points = num_points;
  return p;
}

TEST(WindowPiecesTest, TouchingWindowPiecesJoinTheLargest) {
  // Two sashes of one window 4 cm apart, its frame's top above them, and a window 1 m further on.
  const std::vector<WindowPiece> pieces = {Piece(1.0, 1.5, 0.9, 1.9, true, 500), Piece(1.54, 2.0, 0.9, 1.9, true, 800),
                                           Piece(1.0, 2.0, 1.95, 2.0, true, 100), Piece(3.0, 3.8, 0.9, 1.9, true, 700)};
  EXPECT_EQ(JoinWindowPieces(pieces, 0.1), (std::vector<int>{1, 1, 1, 3}));
  // Closer than the gap only through the frame: the join is transitive.
  EXPECT_EQ(JoinWindowPieces(pieces, 0.05), (std::vector<int>{1, 1, 1, 3}));
  // Off: every piece stays.
  EXPECT_EQ(JoinWindowPieces(pieces, -1.0), (std::vector<int>{0, 1, 2, 3}));
}

TEST(WindowPiecesTest, OnlyWindowsJoinAndACompleteWindowHosts) {
  // A dresser-labelled piece between two window pieces bridges nothing; the complete window hosts
  // the larger unfinished piece.
  std::vector<WindowPiece> pieces = {Piece(1.0, 1.5, 0.9, 1.9, true, 300, true), Piece(1.55, 2.0, 0.9, 1.9, false, 900),
                                     Piece(1.52, 2.2, 0.9, 1.9, true, 900)};
  EXPECT_EQ(JoinWindowPieces(pieces, 0.1), (std::vector<int>{0, 1, 0}));
  // Far apart (30 cm of wall between them): two windows.
  pieces[2] = Piece(1.8, 2.2, 0.9, 1.9, true, 900);
  EXPECT_EQ(JoinWindowPieces(pieces, 0.1), (std::vector<int>{0, 1, 2}));
  // Equal pieces: the lower index hosts; a piece without points never joins.
  const std::vector<WindowPiece> equal = {Piece(1.0, 1.5, 0.9, 1.9, true, 400), Piece(1.5, 2.0, 0.9, 1.9, true, 400),
                                          WindowPiece{OpeningExtent(), true, false, 0}};
  EXPECT_EQ(JoinWindowPieces(equal, 0.1), (std::vector<int>{0, 0, 2}));
  // Touching boxes in the openings of two walls (a corner): two windows.
  const std::vector<WindowPiece> corner = {Piece(1.0, 1.5, 0.9, 1.9, true, 400, false, 0),
                                           Piece(1.5, 2.0, 0.9, 1.9, true, 400, false, 1)};
  EXPECT_EQ(JoinWindowPieces(corner, 0.1), (std::vector<int>{0, 1}));
}

TEST(WindowPiecesTest, EachGroupIsHostedByItsCompleteOrLargestPiece) {
  std::vector<WindowPiece> pieces(6);
  const std::vector<std::size_t> points = {300, 500, 200, 400, 400, 900};
  for (std::size_t i = 0; i < pieces.size(); ++i) pieces[i].num_points = points[i];
  pieces[2].complete = true;
  // Group 7: 0, 1, 2 (2 is complete, though smallest); group 3: 3 and 4 (equal sizes: the lower
  // index); 5 in no group stays, however large.
  EXPECT_EQ(HostsOfGroups({7, 7, 7, 3, 3, -1}, pieces), (std::vector<int>{2, 2, 2, 3, 3, 5}));
  EXPECT_EQ(HostsOfGroups({-1, -1, -1, -1, -1, -1}, pieces), (std::vector<int>{0, 1, 2, 3, 4, 5}));
}


// Shelves 25 cm deep against the wall x = 0, y in [1.2, 1.9], 2 m tall: a back board, five boards
// from the wall to 25 cm, and the front edges of the sides.
std::vector<Eigen::Vector3f> ShelvesAgainstTheWall() {
  std::vector<Eigen::Vector3f> shelves = Pane(0.01, 1.2, 1.9, 0.0, 2.0);
  for (double z : {0.4, 0.8, 1.2, 1.6, 2.0}) {
    for (double x = 0.02; x <= 0.25 + 1e-9; x += 0.02) Append(Pane(x, 1.2, 1.9, z, z), &shelves);
  }
  Append(Pane(0.25, 1.2, 1.22, 0.0, 2.0), &shelves);
  Append(Pane(0.25, 1.88, 1.9, 0.0, 2.0), &shelves);
  return shelves;
}

TEST(CurtainTest, APanelHangingOverAWindowIsACurtain) {
  const mapping::StructureResult room = OneWallRoom();
  const WallOpeningOptions options;
  // A window recessed 6 cm, y in [1, 2], sill at 0.9 m; a floor-length panel 10 cm in front of the
  // wall covering its left 30 cm and 40 cm of wall beside it.
  const std::vector<OpeningExtent> windows = {OpeningBounds(Pane(-0.06, 1.0, 2.0, 0.9, 2.0), room, options)};
  ASSERT_EQ(windows[0].wall, 0);
  EXPECT_NEAR(windows[0].along_min_m, 1.0, 1e-6);
  EXPECT_NEAR(windows[0].along_max_m, 2.0, 1e-6);
  EXPECT_NEAR(windows[0].z_min_m, 0.9, 1e-6);
  const OpeningExtent panel = HangingExtent(Pleats(0.1, 0.6, 1.3, 0.02, 2.2), room, options);
  ASSERT_EQ(panel.wall, 0);
  EXPECT_NEAR(panel.fold_depth_m, 0.045, 0.01);
  EXPECT_NEAR(panel.along_min_m, 0.6, 1e-6);
  EXPECT_NEAR(panel.along_max_m, 1.3, 1e-6);
  EXPECT_NEAR(panel.z_max_m, 2.2, 1e-6);
  EXPECT_GE(CurtainWindow(panel, windows, options), 0);
  // A short curtain from the sill down a little: still over the window.
  EXPECT_GE(CurtainWindow(HangingExtent(Pleats(0.1, 0.8, 2.2, 0.8, 2.1), room, options), windows, options), 0);
}

TEST(CurtainTest, EachPanelNamesTheWindowItHangsOver) {
  const mapping::StructureResult room = OneWallRoom();
  const WallOpeningOptions options;
  // Two windows in the wall: y in [1, 2] and y in [3, 3.8].
  const std::vector<OpeningExtent> windows = {OpeningBounds(Pane(-0.06, 1.0, 2.0, 0.9, 2.0), room, options),
                                              OpeningBounds(Pane(-0.06, 3.0, 3.8, 0.9, 2.0), room, options)};
  // The two panels of the first window's curtain, drawn to its sides, and a panel over the second.
  EXPECT_EQ(CurtainWindow(HangingExtent(Pleats(0.1, 0.6, 1.3, 0.02, 2.2), room, options), windows, options), 0);
  EXPECT_EQ(CurtainWindow(HangingExtent(Pleats(0.1, 1.7, 2.4, 0.02, 2.2), room, options), windows, options), 0);
  EXPECT_EQ(CurtainWindow(HangingExtent(Pleats(0.1, 3.5, 3.95, 0.02, 2.2), room, options), windows, options), 1);
  // Between the windows, overlapping neither by 10 cm: none.
  EXPECT_EQ(CurtainWindow(HangingExtent(Pleats(0.1, 1.95, 3.05, 0.02, 2.2), room, options), windows, options), -1);
}

TEST(CurtainTest, ADoorLeafOrThingsInTheRoomAreNoCurtains) {
  const mapping::StructureResult room = OneWallRoom();
  const WallOpeningOptions options;
  const std::vector<OpeningExtent> windows = {OpeningBounds(Pane(-0.06, 1.0, 2.0, 0.9, 2.0), room, options)};
  // A flat door leaf, opened against the wall over the window: its face has no folds.
  const OpeningExtent leaf = HangingExtent(Pane(0.05, 0.9, 1.7, 0.0, 2.05), room, options);
  ASSERT_EQ(leaf.wall, 0);
  EXPECT_NEAR(leaf.fold_depth_m, 0.0, 1e-6);
  EXPECT_EQ(CurtainWindow(leaf, windows, options), -1);
  // Folded, but 5 cm beside the window, or overlapping it by 5 cm only (< curtain_min_overlap_m).
  const OpeningExtent beside = HangingExtent(Pleats(0.1, 2.05, 2.9, 0.0, 2.05), room, options);
  EXPECT_GT(beside.fold_depth_m, 0.02);
  EXPECT_EQ(CurtainWindow(beside, windows, options), -1);
  EXPECT_EQ(CurtainWindow(HangingExtent(Pleats(0.1, 1.95, 2.8, 0.0, 2.05), room, options), windows, options), -1);
  // A cabinet 60 cm deep in front of the window: most of it stands farther than 30 cm from the wall.
  std::vector<Eigen::Vector3f> cabinet = Pane(0.6, 1.0, 2.0, 0.0, 0.9);
  Append(Pane(0.3, 1.0, 2.0, 0.9, 0.9), &cabinet);
  EXPECT_EQ(HangingExtent(cabinet, room, options).wall, -1);
  // No share required, but nothing near the wall: still no wall.
  WallOpeningOptions any_share = options;
  any_share.curtain_min_share = 0.0;
  EXPECT_EQ(HangingExtent(Pane(0.6, 1.0, 2.0, 0.0, 0.9), room, any_share).wall, -1);
  // Shelves 25 cm deep against the wall over the window: boards from the wall to 25 cm, a back
  // board; their spread is that of a thing with depth, not of folds.
  const OpeningExtent shelf_extent = HangingExtent(ShelvesAgainstTheWall(), room, options);
  ASSERT_EQ(shelf_extent.wall, 0);
  EXPECT_GT(shelf_extent.fold_depth_m, options.curtain_max_fold_depth_m);
  EXPECT_EQ(CurtainWindow(shelf_extent, windows, options), -1);
  // A low folded thing against the wall reaching the sill (70 cm tall): not tall enough.
  EXPECT_EQ(CurtainWindow(HangingExtent(Pleats(0.1, 1.0, 2.0, 0.3, 1.0), room, options), windows, options), -1);
  // Over the window's span but on another wall, or with no window at all.
  OpeningExtent on_second = HangingExtent(Pleats(0.1, 0.6, 1.3, 0.02, 2.2), room, options);
  ASSERT_GE(CurtainWindow(on_second, windows, options), 0);
  on_second.wall = 1;
  EXPECT_EQ(CurtainWindow(on_second, windows, options), -1);
  EXPECT_EQ(CurtainWindow(HangingExtent(Pleats(0.1, 0.6, 1.3, 0.02, 2.2), room, options), {}, options), -1);
}

TEST(DoorTest, MinHorizontalWidthIsTheLeastExtentOverDirections) {
  EXPECT_EQ(MinHorizontalWidth({}), 0.0);
  // A 1 m x 0.3 m rectangle of points turned by 30°: 0.3 m, whatever the turn.
  std::vector<Eigen::Vector3f> points;
  const float c = std::cos(0.5236f), s = std::sin(0.5236f);
  for (double u = 0.0; u <= 1.0 + 1e-9; u += 0.05) {
    for (double v = 0.0; v <= 0.3 + 1e-9; v += 0.05) {
      points.emplace_back(static_cast<float>(c * u - s * v), static_cast<float>(s * u + c * v), 0.5f);
    }
  }
  EXPECT_NEAR(MinHorizontalWidth(points), 0.3, 0.005);
  // Height does not count: a 2 m tall flat pane is as thin as its thickness.
  EXPECT_NEAR(MinHorizontalWidth(Pane(0.2, 1.0, 1.8, 0.0, 2.0)), 0.0, 1e-6);
}

TEST(DoorTest, ADoorLabelNeedsSomethingAsThinAsADoorLeaf) {
  const WallOpeningOptions options;  // 0.4 m
  // An opened leaf 4 cm thick with a handle 6 cm proud, and a strip of the wall beside it.
  std::vector<Eigen::Vector3f> leaf = Pane(0.01, 1.0, 1.8, 0.0, 2.0);
  Append(Pane(0.05, 1.0, 1.8, 0.0, 2.0), &leaf);
  Append(Pane(0.11, 1.1, 1.16, 0.95, 1.05), &leaf);
  Append(Pane(-0.15, 1.8, 2.3, 0.0, 2.0), &leaf);
  EXPECT_FALSE(TooDeepForADoor(leaf, options));
  // A cabinet 60 cm deep whose front a door model fitted: with its top and side seen, too deep.
  std::vector<Eigen::Vector3f> cabinet = Pane(0.6, 1.0, 2.0, 0.0, 0.9);
  for (double x = 0.0; x <= 0.6 + 1e-9; x += 0.02) Append(Pane(x, 1.0, 2.0, 0.9, 0.9), &cabinet);
  EXPECT_TRUE(TooDeepForADoor(cabinet, options));
  // Its front alone is as thin as a door: the check cannot tell them apart.
  EXPECT_FALSE(TooDeepForADoor(Pane(0.6, 1.0, 2.0, 0.0, 0.9), options));
}

TEST(CurtainTest, CurtainLabelsOnThingsWithDepthGo) {
  const mapping::StructureResult room = OneWallRoom();
  const WallOpeningOptions options;
  // A pleated panel hanging 10 cm in front of the wall keeps its label, over a window or not (a
  // drawn curtain hides its window).
  EXPECT_FALSE(CurtainLabelGoes(world::Category::kCurtain, HangingExtent(Pleats(0.1, 0.6, 1.3, 0.02, 2.2), room, options),
                                options));
  EXPECT_FALSE(CurtainLabelGoes(world::Category::kCurtain, HangingExtent(Pleats(0.1, 2.6, 3.6, 0.02, 2.2), room, options),
                                options));
  // A wardrobe's front 60 cm from the wall: it hangs on no wall.
  std::vector<Eigen::Vector3f> wardrobe = Pane(0.6, 2.2, 3.6, 0.0, 2.0);
  Append(Pane(0.3, 2.2, 3.6, 2.0, 2.0), &wardrobe);
  const OpeningExtent wardrobe_extent = HangingExtent(wardrobe, room, options);
  EXPECT_EQ(wardrobe_extent.wall, -1);
  EXPECT_TRUE(CurtainLabelGoes(world::Category::kCurtain, wardrobe_extent, options));
  // Shelves 25 cm deep against the wall: near it, but their boards spread deeper than folds do.
  const OpeningExtent shelf_extent = HangingExtent(ShelvesAgainstTheWall(), room, options);
  ASSERT_EQ(shelf_extent.wall, 0);
  EXPECT_TRUE(CurtainLabelGoes(world::Category::kCurtain, shelf_extent, options));
  // Only curtain labels are this rule's business.
  EXPECT_FALSE(CurtainLabelGoes(world::Category::kCabinet, wardrobe_extent, options));
  EXPECT_FALSE(CurtainLabelGoes(std::nullopt, wardrobe_extent, options));
}

}  // namespace
}  // namespace objscan::scanning
