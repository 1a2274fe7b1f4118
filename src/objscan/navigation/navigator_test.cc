#include "objscan/navigation/navigator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <queue>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"
#include "objscan/sim/ground_truth_occupancy.h"
#include "objscan/sim/test_scenes.h"
#include "objscan/world/procedural/procedural.h"

namespace objscan::navigation {
namespace {

using sim::GroundTruthOccupancy;
using sim::testing::BoxObject;
using sim::testing::Room;

constexpr double kRadius = 0.25;
constexpr double kHeight = 1.8;

// Reference optimum: Dijkstra over the navigator's inflated grid with the same moves as A*
// (8-connected, diagonals only when both straight neighbours are free).
double OptimalGridPathM(const Navigator& nav, const Eigen::Vector2d& start, const Eigen::Vector2d& goal) {
  const OccupancyGrid2D& grid = nav.grid();
  auto free = [&](int x, int y) { return grid.Contains(x, y) && nav.blocked()[grid.Index(x, y)] == 0; };
  std::vector<double> dist(grid.NumCells(), std::numeric_limits<double>::infinity());
  const Eigen::Vector2i s = grid.CellOf(start), g = grid.CellOf(goal);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  dist[grid.Index(s.x(), s.y())] = 0;
  open.emplace(0.0, static_cast<int>(grid.Index(s.x(), s.y())));
  while (!open.empty()) {
    auto [d, i] = open.top();
    open.pop();
    if (d > dist[i]) continue;
    const int x = i % grid.width, y = i / grid.width;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !free(x + dx, y + dy)) continue;
        if (dx != 0 && dy != 0 && (!free(x + dx, y) || !free(x, y + dy))) continue;
        const double nd = d + std::hypot(dx, dy) * grid.cell_size_m;
        const int j = static_cast<int>(grid.Index(x + dx, y + dy));
        if (nd < dist[j]) {
          dist[j] = nd;
          open.emplace(nd, j);
        }
      }
    }
  }
  return dist[grid.Index(g.x(), g.y())];
}

// Distance from p to the axis-aligned rectangle [lo, hi] (0 inside).
double DistanceToRect(const Eigen::Vector2d& p, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const double dx = std::max({lo.x() - p.x(), 0.0, p.x() - hi.x()});
  const double dy = std::max({lo.y() - p.y(), 0.0, p.y() - hi.y()});
  return std::hypot(dx, dy);
}

std::vector<Eigen::Vector2d> Sample(const std::vector<Eigen::Vector2d>& waypoints, double step_m) {
  std::vector<Eigen::Vector2d> samples{waypoints.front()};
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    const double length = (waypoints[i] - waypoints[i - 1]).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(length / step_m)));
    for (int k = 1; k <= n; ++k) samples.push_back(waypoints[i - 1] + (waypoints[i] - waypoints[i - 1]) * k / n);
  }
  return samples;
}

TEST(NavigatorTest, AStarAroundAnObstacleIsWithinFivePercentOfTheOptimum) {
  world::Scene scene = Room(8, 5);
  // A barrier from the bottom wall up to y = 3.5: the way from left to right goes over its top.
  const Eigen::Vector2d barrier_lo(3.8, 0.0), barrier_hi(4.2, 3.5);
  scene.Add(BoxObject({3.8, 0.0, 0}, {4.2, 3.5, 1.0}));
  const GroundTruthOccupancy source(scene);
  NavigatorOptions options;
  options.smooth_path = false;
  const Navigator raw(source, kRadius, kHeight, options);
  const Navigator smooth(source, kRadius, kHeight);
  const Eigen::Vector2d start(1.0, 1.0), goal(7.0, 1.0);

  const double optimum = OptimalGridPathM(raw, start, goal);
  ASSERT_TRUE(std::isfinite(optimum));
  EXPECT_GT(optimum, 1.3 * (goal - start).norm());  // it really has to go around

  const Path2D grid_path = raw.Plan(start, goal);
  ASSERT_EQ(grid_path.status, PlanStatus::kReached);
  EXPECT_LE(grid_path.grid_length_m, 1.05 * optimum);
  EXPECT_GE(grid_path.grid_length_m, optimum - 1e-9);
  // Unsmoothed waypoints are the cell path (start and goal exact): its length is the grid length up
  // to the two end offsets inside their cells.
  EXPECT_NEAR(grid_path.length_m, grid_path.grid_length_m, 2 * 0.05);

  const Path2D path = smooth.Plan(start, goal);
  ASSERT_TRUE(path.ok());
  EXPECT_NEAR(path.grid_length_m, grid_path.grid_length_m, 1e-9);
  EXPECT_LE(path.length_m, 1.05 * optimum);
  EXPECT_LE(path.length_m, path.grid_length_m + 0.05);
  EXPECT_LT(path.waypoints.size(), grid_path.waypoints.size());
  EXPECT_EQ(path.waypoints.front(), start);
  EXPECT_EQ(path.waypoints.back(), goal);
  // Taut path over the barrier: no shorter than going straight to the barrier's inflated corners.
  const Eigen::Vector2d corner_a(3.8 - kRadius, 3.5 + kRadius), corner_b(4.2 + kRadius, 3.5 + kRadius);
  EXPECT_GE(path.length_m, (corner_a - start).norm() + (corner_b - corner_a).norm() + (goal - corner_b).norm() - 1e-6);
  for (std::size_t i = 1; i < path.waypoints.size(); ++i) {
    EXPECT_TRUE(smooth.LineOfSight(path.waypoints[i - 1], path.waypoints[i]));
  }
  // The robot's disk never touches the barrier or the walls.
  for (const auto& p : Sample(path.waypoints, 0.01)) {
    ASSERT_GE(DistanceToRect(p, barrier_lo, barrier_hi), kRadius) << p.transpose();
    ASSERT_GE(std::min({p.x(), p.y(), 8 - p.x(), 5 - p.y()}), kRadius) << p.transpose();
  }
}

TEST(NavigatorTest, EnclosedGoalIsUnreachable) {
  world::Scene scene = Room(8, 5);
  // A closed pen with a free inside.
  scene.Add(BoxObject({5.0, 1.0, 0}, {7.5, 1.1, 1.0}));
  scene.Add(BoxObject({5.0, 3.4, 0}, {7.5, 3.5, 1.0}));
  scene.Add(BoxObject({5.0, 1.0, 0}, {5.1, 3.5, 1.0}));
  scene.Add(BoxObject({7.4, 1.0, 0}, {7.5, 3.5, 1.0}));
  const GroundTruthOccupancy source(scene);
  const Navigator nav(source, kRadius, kHeight);
  const Eigen::Vector2d start(1.0, 1.0), inside(6.25, 2.25);
  ASSERT_TRUE(nav.IsFree(inside));
  const Path2D path = nav.Plan(start, inside);
  EXPECT_EQ(path.status, PlanStatus::kUnreachable);
  EXPECT_FALSE(path.ok());
  EXPECT_TRUE(path.waypoints.empty());
  EXPECT_FALSE(std::isfinite(nav.DistanceField(start)[nav.grid().Index(nav.grid().CellOf(inside).x(),
                                                                           nav.grid().CellOf(inside).y())]));
  // From inside the pen to inside the pen works.
  EXPECT_TRUE(nav.Plan(inside, inside + Eigen::Vector2d(0.3, 0.3)).ok());
}

// A robot whose position became blocked (an obstacle now within its inflation radius) backs off to
// the nearest free cell first; deep inside an obstacle it stays blocked.
TEST(NavigatorTest, BlockedStartEscapesToTheNearestFreeCell) {
  world::Scene scene = Room(4, 4);
  scene.Add(BoxObject({2.0, 2.0, 0}, {2.5, 2.5, 0.7}));
  const GroundTruthOccupancy source(scene);
  const Navigator nav(source, kRadius, kHeight);
  const Eigen::Vector2d start(2.5 + 0.2, 2.2);  // within the robot radius of the box
  ASSERT_FALSE(nav.IsFree(start));
  const Path2D path = nav.Plan(start, {1, 1});
  ASSERT_TRUE(path.ok());
  EXPECT_EQ(path.waypoints.front(), start);
  EXPECT_TRUE(nav.IsFree(path.waypoints[1]));
  EXPECT_LT((path.waypoints[1] - start).norm(), 0.3 + 1e-9);
  NavigatorOptions strict;
  strict.start_escape_m = 0.0;
  strict.start_escape_route_m = 0.0;
  EXPECT_EQ(Navigator(source, kRadius, kHeight, strict).Plan(start, {1, 1}).status, PlanStatus::kStartBlocked);
  // Without the straight move, the route through the inflated cells leaves as well.
  strict.start_escape_route_m = 1.0;
  const Path2D routed = Navigator(source, kRadius, kHeight, strict).Plan(start, {1, 1});
  ASSERT_TRUE(routed.ok());
  EXPECT_EQ(routed.waypoints.front(), start);
}

// A grid given cell by cell (the navigator's input, without a scene).
class GridSource final : public OccupancySource {
 public:
  explicit GridSource(OccupancyGrid2D grid) : grid_(std::move(grid)) {}
  OccupancyGrid2D Grid(double, double, double) const override { return grid_; }

 private:
  OccupancyGrid2D grid_;
};

// A robot wedged in a corridor 0.5 m wide between two occupied walls 2 m long, on floor its
// camera never saw (unknown): no free cell lies within start_escape_m, so it leaves along the
// corridor, the way it came, through unknown and inflated cells but never an occupied one, and plans
// on from there. Without the route (start_escape_route_m 0), or with the corridor closed by an
// occupied cell, its start is blocked.
TEST(NavigatorTest, WedgedStartLeavesAlongARouteThroughCellsNotSeenOccupied) {
  OccupancyGrid2D grid = OccupancyGrid2D::Covering({0.0, 0.0}, {4.0, 4.0}, 0.05, CellState::kFree);
  auto set = [&](double x0, double y0, double x1, double y1, CellState state) {
    for (int iy = 0; iy < grid.height; ++iy) {
      for (int ix = 0; ix < grid.width; ++ix) {
        const Eigen::Vector2d c = grid.CellCenter(ix, iy);
        if (c.x() > x0 && c.x() < x1 && c.y() > y0 && c.y() < y1) grid.cells[grid.Index(ix, iy)] = state;
      }
    }
  };
  set(2.0, 1.0, 4.0, 1.5, CellState::kOccupied);  // walls along the corridor y in [1.5, 2.0]
  set(2.0, 2.0, 4.0, 2.5, CellState::kOccupied);
  set(2.0, 1.5, 3.2, 2.0, CellState::kUnknown);   // its floor, unseen
  const Eigen::Vector2d wedged(2.6, 1.75);  // 0.74 m from the first free cell, at x = 1.86 m
  const Navigator nav(GridSource(grid), kRadius, kHeight);
  ASSERT_FALSE(nav.IsFree(wedged));
  Eigen::Vector2d nearest;
  ASSERT_FALSE(nav.NearestFree(wedged, nav.options().start_escape_m, &nearest)) << "no free cell within 0.3 m";

  const std::vector<Eigen::Vector2d> route = nav.EscapeRoute(wedged, 1.0);
  ASSERT_FALSE(route.empty());
  EXPECT_TRUE(nav.IsFree(route.back()));
  for (std::size_t i = 0; i + 1 < route.size(); ++i) EXPECT_FALSE(nav.IsFree(route[i])) << "stops at the first free cell";
  double length = (route.front() - wedged).norm();
  for (std::size_t i = 0; i < route.size(); ++i) {
    const Eigen::Vector2i c = grid.CellOf(route[i]);
    EXPECT_NE(grid.At(c.x(), c.y()), CellState::kOccupied) << i;
    if (i > 0) length += (route[i] - route[i - 1]).norm();
  }
  EXPECT_LT(route.back().x(), 2.0) << "out of the corridor's open end";
  EXPECT_LE(length, 1.0 + 0.05);

  const Path2D path = nav.Plan(wedged, {0.5, 0.5});
  ASSERT_TRUE(path.ok());
  EXPECT_EQ(path.waypoints.front(), wedged);
  for (const Eigen::Vector2d& p : Sample(path.waypoints, 0.02)) {
    const Eigen::Vector2i c = grid.CellOf(p);
    EXPECT_NE(grid.At(c.x(), c.y()), CellState::kOccupied) << p.transpose();
  }
  Eigen::Vector2d start;
  std::vector<Eigen::Vector2d> via;
  ASSERT_TRUE(nav.StartFrom(wedged, &start, &via));
  EXPECT_EQ(start, route.back());
  EXPECT_EQ(via.size() + 1, route.size());

  NavigatorOptions no_route;
  no_route.start_escape_route_m = 0.0;
  EXPECT_EQ(Navigator(GridSource(grid), kRadius, kHeight, no_route).Plan(wedged, {0.5, 0.5}).status,
            PlanStatus::kStartBlocked);
  EXPECT_TRUE(nav.EscapeRoute(wedged, 0.3).empty()) << "the open end is farther than 0.3 m";
  NavigatorOptions negative;
  negative.start_escape_route_m = -1.0;
  EXPECT_THROW(negative.Validate(), InputError);
  set(1.9, 1.5, 2.1, 2.0, CellState::kOccupied);  // the corridor closed
  EXPECT_EQ(Navigator(GridSource(grid), kRadius, kHeight).Plan(wedged, {0.5, 0.5}).status, PlanStatus::kStartBlocked);
}

TEST(NavigatorTest, BlockedStartAndGoalAreStatuses) {
  world::Scene scene = Room(4, 4);
  scene.Add(BoxObject({2.0, 2.0, 0}, {2.5, 2.5, 0.7}));
  const GroundTruthOccupancy source(scene);
  const Navigator nav(source, kRadius, kHeight);
  EXPECT_EQ(nav.Plan({1, 1}, {2.2, 2.2}).status, PlanStatus::kGoalBlocked);
  EXPECT_EQ(nav.Plan({1, 1}, {2.5 + 0.2, 2.2}).status, PlanStatus::kGoalBlocked);  // within the robot radius
  EXPECT_EQ(nav.Plan({2.2, 2.2}, {1, 1}).status, PlanStatus::kStartBlocked);
  EXPECT_EQ(nav.Plan({1, 1}, {9, 9}).status, PlanStatus::kGoalBlocked);             // off the map
  EXPECT_EQ(nav.Plan({1, 1}, {0.1, 1}).status, PlanStatus::kGoalBlocked);           // against the wall
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(nav.Plan({nan, 1}, {1, 1}).status, PlanStatus::kStartBlocked);
  const Path2D same = nav.Plan({1, 1}, {1, 1});
  EXPECT_TRUE(same.ok());
  EXPECT_DOUBLE_EQ(same.length_m, 0.0);
  Eigen::Vector2d free_xy;
  ASSERT_TRUE(nav.NearestFree({2.2, 2.2}, 1.0, &free_xy));
  EXPECT_TRUE(nav.IsFree(free_xy));
  EXPECT_LT((free_xy - Eigen::Vector2d(2.2, 2.2)).norm(), 0.6);
}

TEST(NavigatorTest, LineOfSightOnTheInflatedGrid) {
  world::Scene scene = Room(4, 4);
  scene.Add(BoxObject({1.9, 1.0, 0}, {2.1, 3.0, 0.7}));
  const GroundTruthOccupancy source(scene);
  const Navigator nav(source, kRadius, kHeight);
  EXPECT_FALSE(nav.LineOfSight({1, 2}, {3, 2}));
  EXPECT_TRUE(nav.LineOfSight({1, 0.5}, {3, 0.5}));
  EXPECT_TRUE(nav.LineOfSight({1, 3.5}, {3, 3.5}));
  EXPECT_FALSE(nav.LineOfSight({1, 0.5}, {3, 3.5}));  // diagonal crossing the box
  EXPECT_TRUE(nav.LineOfSight({1, 1}, {1, 1}));
}

TEST(NavigatorTest, PathCostsMatchTheFullDistanceField) {
  world::Scene scene = Room(8, 5);
  scene.Add(BoxObject({3.8, 0.0, 0}, {4.2, 3.5, 1.0}));
  scene.Add(BoxObject({5.0, 1.0, 0}, {7.5, 1.1, 1.0}));  // a pen, closed on all sides
  scene.Add(BoxObject({5.0, 3.4, 0}, {7.5, 3.5, 1.0}));
  scene.Add(BoxObject({5.0, 1.0, 0}, {5.1, 3.5, 1.0}));
  scene.Add(BoxObject({7.4, 1.0, 0}, {7.5, 3.5, 1.0}));
  const GroundTruthOccupancy source(scene);
  const Navigator nav(source, kRadius, kHeight);
  const Eigen::Vector2d start(1.0, 1.0);
  const std::vector<Eigen::Vector2d> targets = {{2.0, 2.0}, {7.0, 0.5}, {6.25, 2.25}, {4.0, 1.0},
                                                {2.0, 2.0}, {1.0, 1.0}, {7.7, 4.7}};
  const std::vector<double> field = nav.DistanceField(start);
  const std::vector<double> costs = nav.PathCosts(start, targets);
  ASSERT_EQ(costs.size(), targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const Eigen::Vector2i c = nav.grid().CellOf(targets[i]);
    const double expected = nav.IsFree(targets[i]) ? field[nav.grid().Index(c.x(), c.y())]
                                                   : std::numeric_limits<double>::infinity();
    EXPECT_EQ(costs[i], expected) << i;
  }
  EXPECT_TRUE(std::isfinite(costs[1]));
  EXPECT_FALSE(std::isfinite(costs[2]));  // inside the pen
  EXPECT_FALSE(std::isfinite(costs[3]));  // inside the barrier
  EXPECT_EQ(costs[5], 0.0);
  // Same as the A* grid length.
  EXPECT_NEAR(costs[1], nav.Plan(start, targets[1]).grid_length_m, 1e-9);
}

// --- The robot never plans through furniture of a procedural room. ---

// Triangles of every non-floor object clipped to the band and projected to XY.
std::vector<std::vector<Eigen::Vector2d>> ObstaclePolygons(const world::Scene& scene, double z_lo, double z_hi) {
  std::vector<std::vector<Eigen::Vector2d>> polygons;
  for (const auto& o : scene.objects()) {
    if (o.category == world::Category::kFloor) continue;
    for (const auto& t : o.mesh.triangles) {
      std::vector<Eigen::Vector3d> poly;
      for (int k = 0; k < 3; ++k) poly.push_back(o.T_world_object * o.mesh.vertices[t[k]].cast<double>());
      for (int side = 0; side < 2 && !poly.empty(); ++side) {
        const double z0 = side == 0 ? z_lo : z_hi;
        const double sign = side == 0 ? 1.0 : -1.0;
        std::vector<Eigen::Vector3d> out;
        for (std::size_t i = 0; i < poly.size(); ++i) {
          const auto& a = poly[i];
          const auto& b = poly[(i + 1) % poly.size()];
          const double da = sign * (a.z() - z0), db = sign * (b.z() - z0);
          if (da >= 0) out.push_back(a);
          if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
        }
        poly = out;
      }
      if (poly.empty()) continue;
      std::vector<Eigen::Vector2d> xy;
      for (const auto& p : poly) xy.push_back(p.head<2>());
      polygons.push_back(xy);
    }
  }
  return polygons;
}

double DistanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// Distance from p to a convex polygon (0 inside).
double DistanceToPolygon(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& poly) {
  bool inside = poly.size() >= 3;
  double sign = 0;
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[(i + 1) % poly.size()];
    d = std::min(d, DistanceToSegment(p, a, b));
    const double c = (b - a).x() * (p - a).y() - (b - a).y() * (p - a).x();
    if (c != 0) {
      if (sign == 0) sign = c;
      if (c * sign < 0) inside = false;
    }
  }
  return inside && sign != 0 ? 0.0 : d;
}

TEST(NavigatorTest, NeverPlansThroughFurnitureOfProceduralRooms) {
  int planned = 0, attempted = 0;
  for (const std::string& category : world::procedural::RoomCategories()) {
    const world::Scene scene = world::procedural::GenerateRoom(category, 1);
    ASSERT_GT(scene.NumFurniture(), 0u) << category;
    const GroundTruthOccupancy source(scene);
    const Navigator nav(source, kRadius, kHeight);
    const auto polygons = ObstaclePolygons(scene, nav.options().min_obstacle_height_m, kHeight);
    std::vector<Eigen::Vector2d> free_cells;
    const OccupancyGrid2D& grid = nav.grid();
    for (int iy = 0; iy < grid.height; ++iy) {
      for (int ix = 0; ix < grid.width; ++ix) {
        if (nav.blocked()[grid.Index(ix, iy)] == 0) free_cells.push_back(grid.CellCenter(ix, iy));
      }
    }
    ASSERT_GT(free_cells.size(), 100u) << category;
    Rng rng(DeriveSeed(17, attempted));
    for (int trial = 0; trial < 6; ++trial) {
      const Eigen::Vector2d a = free_cells[rng.UniformInt(0, static_cast<int>(free_cells.size()) - 1)];
      const Eigen::Vector2d b = free_cells[rng.UniformInt(0, static_cast<int>(free_cells.size()) - 1)];
      ++attempted;
      const Path2D path = nav.Plan(a, b);
      if (!path.ok()) {
        EXPECT_EQ(path.status, PlanStatus::kUnreachable);
        continue;
      }
      ++planned;
      for (const auto& p : Sample(path.waypoints, 0.02)) {
        for (const auto& poly : polygons) {
          ASSERT_GE(DistanceToPolygon(p, poly), kRadius - 1e-9)
              << category << ": path point " << p.transpose() << " inside the robot radius of furniture";
        }
      }
    }
  }
  EXPECT_GE(planned, attempted / 2);  // most free cells of a room are connected
}

}  // namespace
}  // namespace objscan::navigation
