// Occupancy, floor/wall detection and floor frontiers on an analytic room.
#include <gtest/gtest.h>

#include <cmath>

#include "objscan/eval/ground_truth_votes.h"
#include "objscan/mapping/frontiers.h"
#include "objscan/mapping/occupancy_map.h"
#include "objscan/mapping/planes.h"
#include "objscan/mapping/surface_map.h"
#include "objscan/mapping/testing/analytic_world.h"

namespace objscan::mapping {
namespace {

using testing::AnalyticWorld;

constexpr std::int32_t kFloor = 100, kWall = 101, kBox = 1;

// 4 m x 3 m room, walls 2.4 m high, one box against the +Y wall.
// The floor and the four 2.4 m walls (inner faces x = +-2, y = +-1.5) of a 4 x 3 m room.
AnalyticWorld EmptyRoom() {
  AnalyticWorld w;
  w.Add(Eigen::Vector3d(-2.1, -1.6, -0.05), Eigen::Vector3d(2.1, 1.6, 0.0), kFloor);
  w.Add(Eigen::Vector3d(-2.1, -1.6, 0.0), Eigen::Vector3d(-2.0, 1.6, 2.4), kWall);  // x = -2
  w.Add(Eigen::Vector3d(2.0, -1.6, 0.0), Eigen::Vector3d(2.1, 1.6, 2.4), kWall);    // x = 2
  w.Add(Eigen::Vector3d(-2.1, -1.6, 0.0), Eigen::Vector3d(2.1, -1.5, 2.4), kWall);  // y = -1.5
  w.Add(Eigen::Vector3d(-2.1, 1.5, 0.0), Eigen::Vector3d(2.1, 1.6, 2.4), kWall);    // y = 1.5
  return w;
}

AnalyticWorld Room() {
  AnalyticWorld w = EmptyRoom();
  w.Add(Eigen::Vector3d(-0.5, 1.0, 0.0), Eigen::Vector3d(0.5, 1.5, 0.8), kBox);
  return w;
}

// Share of the map elements of ground-truth instance `id` tagged floor or wall; expects at least
// `min_elements` of them.
double StructuralShare(const SurfaceMap& map, const eval::GroundTruthVotes& votes, std::int32_t id,
                       std::size_t min_elements) {
  std::size_t n = 0, structural = 0;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (votes.Instance(i) != id) continue;
    ++n;
    structural += map.structure(i) != Structure::kNone ? 1 : 0;
  }
  EXPECT_GE(n, min_elements) << "elements of instance " << id;
  return static_cast<double>(structural) / static_cast<double>(std::max<std::size_t>(n, 1));
}

geometry::Pose3 View(const Eigen::Vector3d& position, double yaw_deg, double pitch_deg) {
  return geometry::CameraPoseFromYawPitch(position, geometry::DegToRad(yaw_deg), geometry::DegToRad(pitch_deg));
}

TEST(OccupancyMapTest, FreeOccupiedUnknownAndNavigationGrid) {
  const AnalyticWorld room = Room();
  OccupancyMap occupancy;
  // Looking at the box and the +Y wall from the room centre.
  occupancy.Integrate(room.Render(View(Eigen::Vector3d(0, -0.5, 1.2), 90, -25), nullptr));
  EXPECT_EQ(occupancy.Query(Eigen::Vector3d(0, -0.5, 1.2)), Occupancy::kFree);
  EXPECT_EQ(occupancy.Query(Eigen::Vector3d(0, 0.3, 0.9)), Occupancy::kFree);    // between camera and box
  EXPECT_EQ(occupancy.Query(Eigen::Vector3d(0, 1.02, 0.4)), Occupancy::kOccupied);  // box front face
  EXPECT_EQ(occupancy.Query(Eigen::Vector3d(0, 1.3, 0.4)), Occupancy::kUnknown);  // inside the box
  EXPECT_EQ(occupancy.Query(Eigen::Vector3d(0, 2.0, 1.5)), Occupancy::kUnknown);  // behind the wall
  EXPECT_EQ(occupancy.Query(Eigen::Vector3d(0, -1.4, 1.0)), Occupancy::kUnknown);  // behind the camera
  EXPECT_TRUE(occupancy.IsViewValid(Eigen::Vector3d(0, -0.5, 1.2)));
  EXPECT_FALSE(occupancy.IsViewValid(Eigen::Vector3d(0, 1.3, 0.4)));
  EXPECT_FALSE(occupancy.IsViewValid(Eigen::Vector3d(0, -1.4, 1.0)));
  OccupancyMapOptions with_clearance;
  with_clearance.view_clearance_m = 0.1;
  OccupancyMap cautious(with_clearance);
  cautious.Integrate(room.Render(View(Eigen::Vector3d(0, -0.5, 1.2), 90, -25), nullptr));
  // Behind the camera is unknown, so a clearance sphere around it is not known free.
  EXPECT_FALSE(cautious.IsViewValid(Eigen::Vector3d(0, -0.5, 1.2)));
  EXPECT_TRUE(cautious.IsViewValid(Eigen::Vector3d(0, 0.2, 0.9)));

  const navigation::OccupancyGrid2D grid = occupancy.Grid(0.05, 1.5, 0.05);
  ASSERT_GT(grid.NumCells(), 0u);
  auto state = [&](double x, double y) {
    const Eigen::Vector2i c = grid.CellOf(Eigen::Vector2d(x, y));
    return grid.At(c.x(), c.y());
  };
  EXPECT_EQ(state(0.0, 1.02), navigation::CellState::kOccupied);  // the box's front face
  EXPECT_EQ(state(0.0, 0.3), navigation::CellState::kFree);
  EXPECT_EQ(state(0.0, -1.3), navigation::CellState::kUnknown);
  EXPECT_GT(grid.Count(navigation::CellState::kFree), 100u);

  std::size_t occupied = 0;
  occupancy.ForEachOccupied([&](const Eigen::Vector3d& c, double size_m) {
    EXPECT_NEAR(size_m, 0.05, 1e-9);
    // Occupied voxels lie on surfaces: the floor, the box or the wall.
    const bool on_surface = c.z() < 0.1 || c.y() > 0.95;
    EXPECT_TRUE(on_surface) << c.transpose();
    ++occupied;
  });
  EXPECT_EQ(occupied, occupancy.NumOccupied());
  EXPECT_GT(occupied, 100u);
}

// KnownBounds (kept as rays come in) holds every known voxel and is tight: on each side a known
// voxel lies within three voxels of the box face. Two views, one of them looking at the floor.
TEST(OccupancyMapTest, KnownBoundsHoldTheKnownVoxelsTightly) {
  const AnalyticWorld room = Room();
  OccupancyMap occupancy;
  occupancy.Integrate(room.Render(View(Eigen::Vector3d(0, -0.5, 1.2), 90, -25), nullptr));
  occupancy.Integrate(room.Render(View(Eigen::Vector3d(-1.0, 0.0, 1.0), 200, -40), nullptr));
  const geometry::Aabb3 box = occupancy.KnownBounds();
  ASSERT_FALSE(box.Empty());
  const double r = occupancy.resolution_m();
  Eigen::Vector3d known_min = Eigen::Vector3d::Constant(1e9), known_max = -known_min;
  for (double z = -0.5 * r; z < 3.0; z += r) {
    for (double y = -2.0 + 0.5 * r; y < 2.0; y += r) {
      for (double x = -2.5 + 0.5 * r; x < 2.5; x += r) {
        const Eigen::Vector3d c(x, y, z);
        if (occupancy.Query(c) == Occupancy::kUnknown) continue;
        EXPECT_TRUE(box.Contains(c)) << c.transpose();
        known_min = known_min.cwiseMin(c);
        known_max = known_max.cwiseMax(c);
      }
    }
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(known_min[a] - box.min_m[a], 3.0 * r) << "axis " << a;
    EXPECT_LT(box.max_m[a] - known_max[a], 3.0 * r) << "axis " << a;
  }
}

// The snapshot agrees with Query at every voxel centre of the known bounds (pruned leaves larger than
// a voxel included), and is unknown outside its box.
TEST(OccupancyMapTest, SnapshotAgreesWithQueryEverywhere) {
  const AnalyticWorld room = Room();
  OccupancyMap occupancy;
  occupancy.Integrate(room.Render(View(Eigen::Vector3d(0, -0.5, 1.2), 90, -25), nullptr));
  occupancy.Integrate(room.Render(View(Eigen::Vector3d(-1.0, 0.0, 1.0), 200, -40), nullptr));
  const OccupancySnapshot snap = occupancy.Snapshot(occupancy.KnownBounds());
  ASSERT_GT(snap.cells.size(), 0u);
  std::size_t counts[3] = {0, 0, 0};
  for (int z = 0; z < snap.nz; ++z) {
    for (int y = 0; y < snap.ny; ++y) {
      for (int x = 0; x < snap.nx; ++x) {
        const Eigen::Vector3d c = snap.origin_world + snap.voxel_size_m * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
        const Occupancy expected = occupancy.Query(c);
        ASSERT_EQ(snap.cells[snap.Index(x, y, z)], expected) << c.transpose();
        ASSERT_EQ(snap.At(c.cast<float>()), expected) << c.transpose();
        ++counts[static_cast<int>(expected)];
      }
    }
  }
  EXPECT_GT(counts[static_cast<int>(Occupancy::kFree)], 1000u);
  EXPECT_GT(counts[static_cast<int>(Occupancy::kOccupied)], 100u);
  EXPECT_EQ(snap.At(Eigen::Vector3f(0, 0, 50)), Occupancy::kUnknown);
}

// The navigator takes the band from 2 cm up: floor hits (z ~ 0 with noise) fall in the voxel layer
// [0, 5 cm] and would block the whole floor unless floor end points only clear space.
TEST(OccupancyMapTest, FloorEndPointsClearSpaceButNeverBlock) {
  const AnalyticWorld room = Room();
  auto floor_cells = [&](const OccupancyMapOptions& options, std::size_t* occupied, std::size_t* free) {
    OccupancyMap occupancy(options);
    Rng rng(3);
    occupancy.Integrate(room.Render(View(Eigen::Vector3d(0, -0.5, 1.2), 90, -40), &rng, 0.004, 0.003));
    const navigation::OccupancyGrid2D grid = occupancy.Grid(0.02, 1.8, 0.05);
    *occupied = *free = 0;
    for (double y = -0.2; y < 0.9; y += 0.05) {
      for (double x = -0.6; x < 0.6; x += 0.05) {
        const Eigen::Vector2i c = grid.CellOf(Eigen::Vector2d(x, y));
        *occupied += grid.At(c.x(), c.y()) == navigation::CellState::kOccupied;
        *free += grid.At(c.x(), c.y()) == navigation::CellState::kFree;
      }
    }
    return grid;
  };
  std::size_t occupied = 0, free = 0;
  OccupancyMapOptions plain;
  plain.floor_clearance_m = 0.0;
  floor_cells(plain, &occupied, &free);
  EXPECT_GT(occupied, 50u) << "plain OctoMap: the noisy floor itself is an obstacle";
  const navigation::OccupancyGrid2D grid = floor_cells(OccupancyMapOptions(), &occupied, &free);
  EXPECT_EQ(occupied, 0u);
  EXPECT_GT(free, 300u);  // of 22 x 24 cells in front of the box
  // The box still blocks.
  const Eigen::Vector2i box = grid.CellOf(Eigen::Vector2d(0.0, 1.02));
  EXPECT_EQ(grid.At(box.x(), box.y()), navigation::CellState::kOccupied);
}

struct RoomScan {
  SurfaceMap surface;
  eval::GroundTruthVotes votes;  // each element's ground-truth instance
  OccupancyMap occupancy;
  StructureResult structure;
};

// Half-resolution frames keep the test fast. Depth noise sigma(z) = sigma_base_m + sigma_quadratic * z^2.
void Observe(const AnalyticWorld& room, const geometry::Pose3& T, Rng* rng, RoomScan* scan,
             double sigma_base_m = 0.001, double sigma_quadratic_per_m = 0.0015) {
  platform::CameraIntrinsics half;
  half.width_px = 320;
  half.height_px = 240;
  half.fx_px = half.fy_px = 262.5;
  half.cx_px = 159.5;
  half.cy_px = 119.5;
  const platform::DepthFrame frame = room.Render(T, rng, sigma_base_m, sigma_quadratic_per_m, half);
  FrameAssociation association;
  scan->surface.Integrate(frame, &association);
  scan->votes.Observe(frame, association);
  scan->occupancy.Integrate(frame);
}

TEST(StructureAndFrontierTest, FloorWallsFoundAndFrontiersVanishWhenTheFloorIsSeen) {
  const AnalyticWorld room = Room();
  Rng rng(21);
  RoomScan scan;
  const StructureDetector detector;
  Observe(room, View(Eigen::Vector3d(-1.0, -0.5, 1.2), 0, -30), &rng, &scan);
  scan.structure = detector.Update(&scan.surface);
  ASSERT_TRUE(scan.structure.has_floor);
  const std::vector<FrontierGoal> first = FindFloorFrontiers(scan.surface, scan.occupancy, scan.structure, {});
  EXPECT_FALSE(first.empty()) << "frontiers at the start";
  for (const FrontierGoal& g : first) EXPECT_GE(g.size_cells, 4);

  // Look around from three places until every floor cell has been seen.
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(-1.0, -0.5, 1.2), Eigen::Vector3d(1.0, -0.5, 1.2),
                                   Eigen::Vector3d(0.0, 0.6, 1.2)}) {
    for (int yaw = 0; yaw < 360; yaw += 45) {
      Observe(room, View(p, yaw, -35), &rng, &scan);
      Observe(room, View(p, yaw + 22.5, -60), &rng, &scan);
    }
  }
  scan.structure = detector.Update(&scan.surface);
  ASSERT_TRUE(scan.structure.has_floor);
  EXPECT_NEAR(scan.structure.floor_height_m, 0.0, 0.01);
  ASSERT_EQ(scan.structure.walls.size(), 4u);
  for (const WallPlane& w : scan.structure.walls) {
    // Axis-aligned, facing into the room, at the true inner faces.
    const double ax = std::fabs(w.normal.x()), ay = std::fabs(w.normal.y());
    EXPECT_GT(std::max(ax, ay), 0.999);
    const double expected = ax > ay ? 2.0 : 1.5;
    EXPECT_NEAR(-w.offset_m, expected, 0.015) << w.normal.transpose();
  }
  // Tags agree with the ground truth.
  std::size_t floor_ok = 0, floor_n = 0, wall_ok = 0, wall_n = 0, box_structural = 0, box_n = 0;
  for (std::size_t i = 0; i < scan.surface.size(); ++i) {
    const std::int32_t g = scan.votes.Instance(i);
    const Structure s = scan.surface.structure(i);
    if (g == kFloor) {
      ++floor_n;
      floor_ok += s == Structure::kFloor ? 1 : 0;
    } else if (g == kWall) {
      ++wall_n;
      wall_ok += s == Structure::kWall ? 1 : 0;
    } else if (g == kBox) {
      ++box_n;
      box_structural += s != Structure::kNone ? 1 : 0;
    }
  }
  EXPECT_GT(static_cast<double>(floor_ok) / floor_n, 0.97);
  EXPECT_GT(static_cast<double>(wall_ok) / wall_n, 0.95);
  ASSERT_GT(box_n, 1000u);
  // Only the box's bottom edge row (within tolerance of the floor) may be tagged.
  EXPECT_LT(static_cast<double>(box_structural) / box_n, 0.03);

  const std::vector<FrontierGoal> last = FindFloorFrontiers(scan.surface, scan.occupancy, scan.structure, {});
  EXPECT_TRUE(last.empty()) << last.size() << " frontier goals left, largest " << last.front().size_cells
                            << " cells at " << last.front().centroid_m.transpose();
}

// An L-shaped room (a solid block fills the +X+Y corner) with a tall wardrobe against the -Y wall:
// the two inner walls of the L are walls although the other arm of the room lies behind their
// planes, and the wardrobe's big front face is not a wall.
TEST(StructureTest, LShapedRoomHasInnerWallsAndAWardrobeIsNoWall) {
  AnalyticWorld room = EmptyRoom();
  room.Add(Eigen::Vector3d(1.0, 0.5, 0.0), Eigen::Vector3d(2.0, 1.5, 2.4), kWall);      // the notch
  room.Add(Eigen::Vector3d(-1.0, -1.5, 0.0), Eigen::Vector3d(0.6, -1.0, 2.0), kBox);    // wardrobe
  Rng rng(5);
  RoomScan scan;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(-1.0, 0.2, 1.2), Eigen::Vector3d(1.3, -0.6, 1.2),
                                   Eigen::Vector3d(0.0, 0.9, 1.2)}) {
    for (int yaw = 0; yaw < 360; yaw += 45) Observe(room, View(p, yaw, -30), &rng, &scan);
  }
  scan.structure = StructureDetector().Update(&scan.surface);
  // Expected inner faces as (normal, offset): n . x = offset with n pointing into the room.
  struct Face {
    Eigen::Vector3d normal;
    double offset_m;
  };
  const std::vector<Face> faces = {{Eigen::Vector3d(1, 0, 0), -2.0},  {Eigen::Vector3d(-1, 0, 0), -2.0},
                                   {Eigen::Vector3d(0, 1, 0), -1.5},  {Eigen::Vector3d(0, -1, 0), -1.5},
                                   {Eigen::Vector3d(-1, 0, 0), -1.0}, {Eigen::Vector3d(0, -1, 0), -0.5}};
  std::vector<int> found(faces.size(), 0);
  for (const WallPlane& w : scan.structure.walls) {
    bool matched = false;
    for (std::size_t k = 0; k < faces.size(); ++k) {
      if (w.normal.dot(faces[k].normal) > 0.999 && std::fabs(w.offset_m - faces[k].offset_m) < 0.02) {
        ++found[k];
        matched = true;
      }
    }
    EXPECT_TRUE(matched) << "unexpected wall n=" << w.normal.transpose() << " d=" << w.offset_m;
  }
  for (std::size_t k = 0; k < faces.size(); ++k) {
    EXPECT_EQ(found[k], 1) << "face n=" << faces[k].normal.transpose() << " d=" << faces[k].offset_m;
  }
  // The wardrobe stays an object.
  EXPECT_LT(StructuralShare(scan.surface, scan.votes, kBox, 5000), 0.03);
}

// A 2 m wardrobe in the corner of a 2.4 m room: the wall behind it is seen only beside it, so no
// wall overlaps its front along the wall; but that wall rises well above it, so its front is
// furniture, not a wall. With the height rule off (furniture_top_margin_m = 0) it would be a wall.
TEST(StructureTest, AWardrobeInACornerIsNoWall) {
  AnalyticWorld room = EmptyRoom();
  room.Add(Eigen::Vector3d(-2.0, -1.5, 0.0), Eigen::Vector3d(-0.6, -0.9, 2.0), kBox);   // wardrobe
  Rng rng(7);
  RoomScan scan;
  // Level and downward views: the level ones see the wall above the wardrobe's top.
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(-0.5, 0.5, 1.2), Eigen::Vector3d(1.0, -0.5, 1.2)}) {
    for (int yaw = 0; yaw < 360; yaw += 45) {
      Observe(room, View(p, yaw, -25), &rng, &scan);
      Observe(room, View(p, yaw + 22.5, 0), &rng, &scan);
    }
  }
  const auto wardrobe_front_is_wall = [](const StructureResult& structure) {
    for (const WallPlane& w : structure.walls) {
      if (w.normal.dot(Eigen::Vector3d(0, 1, 0)) > 0.999 && std::fabs(w.offset_m - (-0.9)) < 0.03) return true;
    }
    return false;
  };
  StructureOptions overlap_only;
  overlap_only.furniture_top_margin_m = 0.0;
  scan.structure = StructureDetector(overlap_only).Update(&scan.surface);
  EXPECT_TRUE(wardrobe_front_is_wall(scan.structure)) << "the case the height rule is for";
  EXPECT_GT(StructuralShare(scan.surface, scan.votes, kBox, 5000), 0.2);

  scan.structure = StructureDetector().Update(&scan.surface);
  EXPECT_FALSE(wardrobe_front_is_wall(scan.structure));
  EXPECT_EQ(scan.structure.walls.size(), 4u);
  EXPECT_LT(StructuralShare(scan.surface, scan.votes, kBox, 5000), 0.03);
}

// An L-shaped room (a block fills x in [0.5, 2], y in [0, 1.5]) whose step face y = 0 has been seen
// only from close by, looking down, so up to about 1.3 m, while the wall 1.5 m behind it (y = 1.5)
// and the other step face x = 0.5 joining the two were seen to the top. The step is a wall, not a
// wardrobe front: the full-height wall joining it to the wall behind runs no farther into the room.
TEST(StructureTest, TheStepOfAnLShapedRoomSeenOnlyLowIsAWall) {
  AnalyticWorld room = EmptyRoom();
  room.Add(Eigen::Vector3d(0.5, 0.0, 0.0), Eigen::Vector3d(2.0, 1.5, 2.4), kWall);
  Rng rng(13);
  RoomScan scan;
  // Level views from high up in the open arm of the L, which cannot see the y = 0 face.
  for (int yaw = 0; yaw < 360; yaw += 45) Observe(room, View(Eigen::Vector3d(-1.5, 0.75, 1.8), yaw, 0), &rng, &scan);
  Observe(room, View(Eigen::Vector3d(1.2, -1.2, 1.4), 90, -30), &rng, &scan);
  Observe(room, View(Eigen::Vector3d(-1.0, -1.0, 1.2), 270, -30), &rng, &scan);
  scan.structure = StructureDetector().Update(&scan.surface);
  bool step = false, joint = false;
  for (const WallPlane& w : scan.structure.walls) {
    if (w.normal.dot(Eigen::Vector3d(0, -1, 0)) > 0.999 && std::fabs(w.offset_m) < 0.02) {
      step = true;
      EXPECT_LT(w.z_max_m, 1.6) << "the step is meant to be seen low only";
    }
    joint = joint || (w.normal.dot(Eigen::Vector3d(-1, 0, 0)) > 0.999 && std::fabs(w.offset_m - (-0.5)) < 0.02);
  }
  EXPECT_TRUE(step);
  EXPECT_TRUE(joint);
}

// A window pane recessed 5-7 cm into the x = 2 wall (a 1.4 x 1.4 m opening): the wall is found once,
// on its own plane (not on a plane fitted through wall and pane), and the pane is not tagged wall.
TEST(StructureTest, ARecessedWindowDoesNotPullTheWallPlane) {
  constexpr std::int32_t kPane = 2;
  for (double depth_m : {0.05, 0.06, 0.07}) {
    SCOPED_TRACE(depth_m);
    AnalyticWorld room;
    room.Add(Eigen::Vector3d(-2.1, -1.6, -0.05), Eigen::Vector3d(2.1, 1.6, 0.0), kFloor);
    room.Add(Eigen::Vector3d(-2.1, -1.6, 0.0), Eigen::Vector3d(-2.0, 1.6, 2.4), kWall);  // x = -2
    room.Add(Eigen::Vector3d(-2.1, -1.6, 0.0), Eigen::Vector3d(2.1, -1.5, 2.4), kWall);  // y = -1.5
    room.Add(Eigen::Vector3d(-2.1, 1.5, 0.0), Eigen::Vector3d(2.1, 1.6, 2.4), kWall);    // y = 1.5
    // x = 2 around the opening y in [-0.5, 0.9], z in [0.6, 2.0].
    room.Add(Eigen::Vector3d(2.0, -1.6, 0.0), Eigen::Vector3d(2.1, -0.5, 2.4), kWall);
    room.Add(Eigen::Vector3d(2.0, 0.9, 0.0), Eigen::Vector3d(2.1, 1.6, 2.4), kWall);
    room.Add(Eigen::Vector3d(2.0, -0.5, 0.0), Eigen::Vector3d(2.1, 0.9, 0.6), kWall);
    room.Add(Eigen::Vector3d(2.0, -0.5, 2.0), Eigen::Vector3d(2.1, 0.9, 2.4), kWall);
    room.Add(Eigen::Vector3d(2.0 + depth_m, -0.5, 0.6), Eigen::Vector3d(2.02 + depth_m, 0.9, 2.0), kPane);
    Rng rng(11);
    RoomScan scan;
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(-1.0, 0.0, 1.2), Eigen::Vector3d(0.5, -0.5, 1.2)}) {
      for (int yaw = 0; yaw < 360; yaw += 45) Observe(room, View(p, yaw, -20), &rng, &scan);
    }
    scan.structure = StructureDetector().Update(&scan.surface);
    int at_wall = 0;
    for (const WallPlane& w : scan.structure.walls) {
      const bool facing = w.normal.dot(Eigen::Vector3d(-1, 0, 0)) > 0.99;
      EXPECT_FALSE(facing && std::fabs(w.offset_m - (-2.0)) >= 0.01)
          << "a plane off the wall: n=" << w.normal.transpose() << " d=" << w.offset_m;
      at_wall += facing && std::fabs(w.offset_m - (-2.0)) < 0.01;
    }
    EXPECT_EQ(at_wall, 1);
    EXPECT_EQ(scan.structure.walls.size(), 4u);
    EXPECT_LT(StructuralShare(scan.surface, scan.votes, kPane, 2000), 0.05);
    if (depth_m > 0.065) {
      // The case the opening depth is for: counting the pane as behind the wall rejects the wall.
      StructureOptions old_rule;
      old_rule.wall_behind_min_depth_m = 2.0 * old_rule.plane_tolerance_m;
      EXPECT_EQ(StructureDetector(old_rule).Update(&scan.surface).walls.size(), 3u);
    }
  }
}

// A curtain 8 cm in front of the y = 1.5 wall, 2.2 m wide and 2.3 m tall: the wall stays the wall
// (the smaller plane a few cm from it goes, whichever side it is on) and the curtain is no structure.
TEST(StructureTest, ACurtainInFrontOfAWallIsNoWall) {
  constexpr std::int32_t kCurtain = 3;
  AnalyticWorld room = EmptyRoom();
  room.Add(Eigen::Vector3d(-1.4, 1.40, 0.05), Eigen::Vector3d(0.8, 1.42, 2.35), kCurtain);
  Rng rng(17);
  RoomScan scan;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(-1.0, -0.5, 1.2), Eigen::Vector3d(1.0, -0.8, 1.2)}) {
    for (int yaw = 0; yaw < 360; yaw += 45) Observe(room, View(p, yaw, -15), &rng, &scan);
  }
  scan.structure = StructureDetector().Update(&scan.surface);
  int at_wall = 0, at_curtain = 0;
  for (const WallPlane& w : scan.structure.walls) {
    if (w.normal.dot(Eigen::Vector3d(0, -1, 0)) < 0.99) continue;
    at_wall += std::fabs(w.offset_m - (-1.5)) < 0.02;
    at_curtain += std::fabs(w.offset_m - (-1.4)) < 0.03;
  }
  EXPECT_EQ(at_wall, 1);
  EXPECT_EQ(at_curtain, 0);
  EXPECT_EQ(scan.structure.walls.size(), 4u);
  EXPECT_LT(StructuralShare(scan.surface, scan.votes, kCurtain, 5000), 0.05);
}

// A long room seen from afar with a noisy sensor (sigma 2 mm + 2.5 mm/m^2): bins a few degrees off a
// wall collect enough votes to be evaluated, and their plane fits converge onto that wall. Each wall
// is listed once all the same.
TEST(StructureTest, EachWallIsFoundOnceUnderFarRangeNoise) {
  AnalyticWorld room;
  room.Add(Eigen::Vector3d(-3.1, -1.6, -0.05), Eigen::Vector3d(3.1, 1.6, 0.0), kFloor);
  room.Add(Eigen::Vector3d(-3.1, -1.6, 0.0), Eigen::Vector3d(-3.0, 1.6, 2.6), kWall);
  room.Add(Eigen::Vector3d(3.0, -1.6, 0.0), Eigen::Vector3d(3.1, 1.6, 2.6), kWall);
  room.Add(Eigen::Vector3d(-3.1, -1.6, 0.0), Eigen::Vector3d(3.1, -1.5, 2.6), kWall);
  room.Add(Eigen::Vector3d(-3.1, 1.5, 0.0), Eigen::Vector3d(3.1, 1.6, 2.6), kWall);
  Rng rng(19);
  RoomScan scan;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(-2.0, 0.0, 1.3), Eigen::Vector3d(2.0, 0.0, 1.3)}) {
    for (int yaw = 0; yaw < 360; yaw += 30) Observe(room, View(p, yaw, -10), &rng, &scan, 0.002, 0.0025);
  }
  const StructureResult structure = StructureDetector().Update(&scan.surface);
  EXPECT_EQ(structure.walls.size(), 4u);
  for (std::size_t i = 0; i < structure.walls.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const WallPlane& a = structure.walls[i];
      const WallPlane& b = structure.walls[j];
      EXPECT_FALSE(a.normal.dot(b.normal) > 0.99 && std::fabs(a.offset_m - b.offset_m) < 0.1)
          << "twice: n=" << a.normal.transpose() << " d=" << a.offset_m;
    }
  }
}

}  // namespace
}  // namespace objscan::mapping

namespace objscan::mapping {
namespace {

// A ceiling (houses have them; the paper's rooms are open at the top) is structure: tagged ceiling,
// not left to become an object; a lamp hanging under it faces down below the search height and
// stays an object.
TEST(StructureTest, CeilingIsStructureAndNoObject) {
  constexpr std::int32_t kCeiling = 102, kLamp = 2;
  AnalyticWorld room = EmptyRoom();
  room.Add(Eigen::Vector3d(-2.1, -1.6, 2.4), Eigen::Vector3d(2.1, 1.6, 2.45), kCeiling);
  room.Add(Eigen::Vector3d(-0.3, -0.3, 1.8), Eigen::Vector3d(0.3, 0.3, 1.95), kLamp);
  Rng rng(5);
  RoomScan scan;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(-1.0, -0.5, 1.2), Eigen::Vector3d(0.5, 0.0, 1.2)}) {
    for (int yaw = 0; yaw < 360; yaw += 60) {
      Observe(room, View(p, yaw, 40), &rng, &scan);
      Observe(room, View(p, yaw + 30, -30), &rng, &scan);
    }
  }
  const StructureResult structure = StructureDetector().Update(&scan.surface);
  ASSERT_TRUE(structure.has_ceiling);
  EXPECT_NEAR(structure.ceiling_height_m, 2.4, 0.01);
  EXPECT_GT(structure.num_ceiling_elements, 1000u);
  EXPECT_GT(StructuralShare(scan.surface, scan.votes, kCeiling, 1000), 0.95);
  EXPECT_LT(StructuralShare(scan.surface, scan.votes, kLamp, 200), 0.05);
  // Without a ceiling nothing is tagged ceiling.
  RoomScan open;
  for (int yaw = 0; yaw < 360; yaw += 60) Observe(EmptyRoom(), View(Eigen::Vector3d(0, 0, 1.2), yaw, 40), &rng, &open);
  EXPECT_FALSE(StructureDetector().Update(&open.surface).has_ceiling);
}

}  // namespace
}  // namespace objscan::mapping
