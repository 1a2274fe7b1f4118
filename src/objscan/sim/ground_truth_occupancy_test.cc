#include "objscan/sim/ground_truth_occupancy.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"
#include "objscan/geometry/mesh.h"

namespace objscan::sim {
namespace {

using navigation::CellState;
using navigation::OccupancyGrid2D;

world::SceneObject Box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                       world::Category category = world::Category::kCabinet) {
  world::SceneObject o;
  o.category = category;
  o.mesh = geometry::MakeBox(lo, hi);
  return o;
}

TEST(GroundTruthOccupancyTest, BoxInTheBandOccupiesExactlyTheCellsItTouches) {
  world::Scene scene("box");
  // Footprint [1.02, 1.48] x [0.51, 0.74]: cells 20..29 in X and 10..14 in Y on a 5 cm grid at 0.
  scene.Add(Box(Eigen::Vector3d(1.02, 0.51, 0.0), Eigen::Vector3d(1.48, 0.74, 0.8)));
  // Corners of the grid extent (tiny boxes in the band) pin the grid origin to (0, 0).
  scene.Add(Box(Eigen::Vector3d(0.5, 0.0, 0.1), Eigen::Vector3d(0.5, 0.0, 0.1)));
  scene.Add(Box(Eigen::Vector3d(0.5, 0.0, 0.1), Eigen::Vector3d(0.51, 0.01, 0.11)));
  const GroundTruthOccupancy source(scene, 0.5);
  const OccupancyGrid2D grid = source.Grid(0.02, 1.8, 0.05);
  EXPECT_NEAR(grid.origin_m.x(), 0.0, 1e-12);
  EXPECT_NEAR(grid.origin_m.y(), -0.5, 1e-12);
  for (int iy = 0; iy < grid.height; ++iy) {
    for (int ix = 0; ix < grid.width; ++ix) {
      const Eigen::Vector2d c = grid.CellCenter(ix, iy);
      const bool in_box = c.x() > 1.0 && c.x() < 1.5 && c.y() > 0.5 && c.y() < 0.75;
      const bool in_marker = c.x() > 0.45 && c.x() < 0.55 && c.y() > -0.05 && c.y() < 0.05;
      if (in_marker) continue;
      EXPECT_EQ(grid.At(ix, iy) == CellState::kOccupied, in_box) << ix << "," << iy;
    }
  }
  EXPECT_EQ(grid.Count(CellState::kUnknown), 0u);  // no floor objects: everything is floor
}

TEST(GroundTruthOccupancyTest, OnlyTheRobotsHeightBandCounts) {
  world::Scene scene("band");
  scene.Add(Box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 0.01)));       // rug: below the band
  scene.Add(Box(Eigen::Vector3d(2, 0, 2.0), Eigen::Vector3d(3, 1, 2.2)));      // shelf above the robot
  scene.Add(Box(Eigen::Vector3d(4, 0, 1.0), Eigen::Vector3d(5, 1, 2.5)));      // cabinet hanging into it
  const GroundTruthOccupancy source(scene, 0.2);
  const OccupancyGrid2D grid = source.Grid(0.02, 1.8, 0.05);
  auto state = [&](double x, double y) {
    const Eigen::Vector2i c = grid.CellOf(Eigen::Vector2d(x, y));
    return grid.At(c.x(), c.y());
  };
  EXPECT_EQ(state(0.5, 0.5), CellState::kFree);
  EXPECT_EQ(state(2.5, 0.5), CellState::kFree);
  EXPECT_EQ(state(4.5, 0.5), CellState::kOccupied);
  EXPECT_EQ(state(4.02, 0.02), CellState::kOccupied);
  EXPECT_EQ(state(3.5, 0.5), CellState::kFree);
  // With a taller robot the shelf blocks too.
  const OccupancyGrid2D tall = source.Grid(0.02, 2.1, 0.05);
  const Eigen::Vector2i c = tall.CellOf(Eigen::Vector2d(2.5, 0.5));
  EXPECT_EQ(tall.At(c.x(), c.y()), CellState::kOccupied);
}

TEST(GroundTruthOccupancyTest, CellsWithoutFloorAreUnknown) {
  world::Scene scene("floor");
  world::SceneObject floor;
  floor.category = world::Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(0, 0, 2, 2);
  scene.Add(floor);
  scene.Add(Box(Eigen::Vector3d(0.9, 0.9, 0), Eigen::Vector3d(1.1, 1.1, 1.0)));
  const GroundTruthOccupancy source(scene, 1.0);  // grid reaches 1 m beyond the box, past the floor
  const OccupancyGrid2D grid = source.Grid(0.02, 1.8, 0.05);
  auto state = [&](double x, double y) {
    const Eigen::Vector2i c = grid.CellOf(Eigen::Vector2d(x, y));
    return grid.At(c.x(), c.y());
  };
  EXPECT_EQ(state(1.0, 1.0), CellState::kOccupied);
  EXPECT_EQ(state(0.5, 0.5), CellState::kFree);
  EXPECT_EQ(state(0.03, 1.97), CellState::kFree);
  EXPECT_EQ(state(-0.03, 1.0), CellState::kUnknown);
  EXPECT_EQ(state(1.0, 2.04), CellState::kUnknown);
  EXPECT_EQ(grid.At(-1, 0), CellState::kUnknown);  // beyond the grid
}

TEST(GroundTruthOccupancyTest, RejectsEmptySceneAndBadBand) {
  EXPECT_THROW(GroundTruthOccupancy(world::Scene("empty")), InputError);
  world::Scene scene("box");
  scene.Add(Box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)));
  const GroundTruthOccupancy source(scene);
  EXPECT_THROW(source.Grid(1.0, 0.5, 0.05), InputError);
  EXPECT_THROW(source.Grid(0.02, 1.8, 0.0), InputError);
}

}  // namespace
}  // namespace objscan::sim
