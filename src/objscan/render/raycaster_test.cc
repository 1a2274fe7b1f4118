#include "objscan/render/raycaster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"
#include "objscan/geometry/mesh.h"

namespace objscan::render {
namespace {

// A unit box [0,1]^3 (instance 1) and a floor quad z = -1 (instance 2).
world::Scene BoxAndFloor() {
  world::Scene scene("box_and_floor");
  world::SceneObject box;
  box.instance_id = 1;
  box.mesh = geometry::MakeBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  scene.Add(box);
  world::SceneObject floor;
  floor.instance_id = 2;
  floor.category = world::Category::kFloor;
  floor.mesh = geometry::MakeQuadXY(-10, -10, 10, 10);
  floor.T_world_object.translation() = Eigen::Vector3d(0, 0, -1);
  scene.Add(floor);
  return scene;
}

TEST(RaycasterTest, HitsBoxFaceWithDistanceInstanceAndOutwardNormal) {
  const Raycaster caster(BoxAndFloor().BuildTriangleSoup());
  EXPECT_EQ(caster.NumTriangles(), 14u);
  // From -X towards the box face x = 0 at (0, 0.3, 0.6); direction of length 2 halves t.
  const RayHit hit = caster.CastRay(Eigen::Vector3d(-2.5, 0.3, 0.6), Eigen::Vector3d(2, 0, 0));
  ASSERT_TRUE(hit.Hit());
  EXPECT_EQ(hit.instance_id, 1);
  EXPECT_NEAR(hit.distance, 1.25f, 1e-6);
  EXPECT_NEAR(hit.normal_world.x(), -1.f, 1e-6);
  EXPECT_NEAR(hit.normal_world.norm(), 1.f, 1e-6);
  EXPECT_EQ(caster.TriangleInstance(hit.triangle), 1);

  const RayHit down = caster.CastRay(Eigen::Vector3d(3, 3, 0), Eigen::Vector3d(0, 0, -1));
  ASSERT_TRUE(down.Hit());
  EXPECT_EQ(down.instance_id, 2);
  EXPECT_NEAR(down.distance, 1.f, 1e-6);
  EXPECT_NEAR(down.normal_world.z(), 1.f, 1e-6);

  const RayHit miss = caster.CastRay(Eigen::Vector3d(3, 3, 0), Eigen::Vector3d(0, 0, 1));
  EXPECT_FALSE(miss.Hit());
  EXPECT_EQ(miss.instance_id, world::kNoInstance);
  // t range: the box face at t = 2.5 lies beyond t_max = 2.
  EXPECT_FALSE(caster.CastRay(Eigen::Vector3d(-2.5, 0.3, 0.6), Eigen::Vector3d(1, 0, 0), 0.0, 2.0).Hit());
}

TEST(RaycasterTest, BatchMatchesSingleRaysForAnyThreadCount) {
  const Raycaster caster(BoxAndFloor().BuildTriangleSoup());
  Rng rng(5);
  RayBatch batch;
  const int n = 5000;  // not a multiple of the packet or block size
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) batch.origins_xyz.push_back(static_cast<float>(rng.Uniform(-3, 3)));
    for (int k = 0; k < 3; ++k) batch.directions_xyz.push_back(static_cast<float>(rng.Uniform(-1, 1)));
  }
  std::vector<RayHit> one, two;
  caster.Cast(batch, &one, 1);
  caster.Cast(batch, &two, 3);
  ASSERT_EQ(one.size(), static_cast<std::size_t>(n));
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d o(batch.origins_xyz[3 * i], batch.origins_xyz[3 * i + 1], batch.origins_xyz[3 * i + 2]);
    const Eigen::Vector3d d(batch.directions_xyz[3 * i], batch.directions_xyz[3 * i + 1],
                            batch.directions_xyz[3 * i + 2]);
    const RayHit single = caster.CastRay(o, d);
    ASSERT_EQ(one[i].instance_id, single.instance_id) << i;
    ASSERT_EQ(two[i].instance_id, single.instance_id) << i;
    if (single.Hit()) {
      ++hits;
      EXPECT_EQ(one[i].distance, two[i].distance);
      EXPECT_NEAR(one[i].distance, single.distance, 1e-5f * single.distance);
    }
  }
  EXPECT_GT(hits, n / 4);
}

TEST(RaycasterTest, SharedOriginBatch) {
  const Raycaster caster(BoxAndFloor().BuildTriangleSoup());
  RayBatch batch;
  batch.origins_xyz = {-1.f, 0.5f, 0.5f};
  batch.directions_xyz = {1, 0, 0, -1, 0, 0, 0, 0, -1};
  std::vector<RayHit> hits;
  caster.Cast(batch, &hits);
  ASSERT_EQ(hits.size(), 3u);
  EXPECT_EQ(hits[0].instance_id, 1);
  EXPECT_NEAR(hits[0].distance, 1.f, 1e-6);
  EXPECT_FALSE(hits[1].Hit());
  EXPECT_EQ(hits[2].instance_id, 2);
  EXPECT_NEAR(hits[2].distance, 1.5f, 1e-6);
}

TEST(RaycasterTest, RejectsBadInput) {
  const Raycaster caster(BoxAndFloor().BuildTriangleSoup());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(caster.CastRay(Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d(1, 0, 0)), InputError);
  EXPECT_THROW(caster.CastRay(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, nan, 0)), InputError);
  EXPECT_THROW(caster.CastRay(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 2.0, 1.0), InputError);
  EXPECT_THROW(caster.SegmentBlocked(Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d(1, 0, 0)), InputError);
  RayBatch ragged;
  ragged.origins_xyz = {0, 0, 0, 1, 1, 1};
  ragged.directions_xyz = {1, 0, 0, 1, 0, 0, 1, 0, 0};
  std::vector<RayHit> hits;
  EXPECT_THROW(caster.Cast(ragged, &hits), InputError);

  world::TriangleSoup bad_index;
  bad_index.vertices_xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  bad_index.triangles = {0, 1, 3};
  bad_index.triangle_instance = {1};
  EXPECT_THROW(Raycaster{bad_index}, InputError);
  world::TriangleSoup bad_vertex = bad_index;
  bad_vertex.triangles = {0, 1, 2};
  bad_vertex.vertices_xyz[4] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(Raycaster{bad_vertex}, InputError);
}

TEST(RaycasterTest, EmptySoupMissesEverything) {
  const Raycaster caster{world::TriangleSoup()};
  EXPECT_FALSE(caster.CastRay(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)).Hit());
  EXPECT_FALSE(caster.SegmentBlocked(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)));
}

TEST(RaycasterTest, SegmentBlocked) {
  const Raycaster caster(BoxAndFloor().BuildTriangleSoup());
  // Through the box.
  EXPECT_TRUE(caster.SegmentBlocked(Eigen::Vector3d(-1, 0.5, 0.5), Eigen::Vector3d(2, 0.5, 0.5)));
  // Beside it.
  EXPECT_FALSE(caster.SegmentBlocked(Eigen::Vector3d(-1, 1.5, 0.5), Eigen::Vector3d(2, 1.5, 0.5)));
  // Ending on the box surface: the end margin keeps the target surface from blocking.
  EXPECT_FALSE(caster.SegmentBlocked(Eigen::Vector3d(-1, 0.5, 0.5), Eigen::Vector3d(0, 0.5, 0.5), 1e-3));
  // Stopping short of the box.
  EXPECT_FALSE(caster.SegmentBlocked(Eigen::Vector3d(-1, 0.5, 0.5), Eigen::Vector3d(-0.1, 0.5, 0.5)));
  // Batched form agrees.
  const float from[6] = {-1, 0.5, 0.5, -1, 1.5, 0.5};
  const float to[6] = {2, 0.5, 0.5, 2, 1.5, 0.5};
  std::uint8_t blocked[2] = {7, 7};
  caster.SegmentsBlocked(from, to, 2, 1e-3, blocked);
  EXPECT_EQ(blocked[0], 1);
  EXPECT_EQ(blocked[1], 0);
}

TEST(RaycasterTest, ProbeTellsInsideFromOutside) {
  const Raycaster caster(BoxAndFloor().BuildTriangleSoup());
  const PointProbe inside = caster.Probe(Eigen::Vector3d(0.5, 0.5, 0.4));
  EXPECT_TRUE(inside.inside);
  EXPECT_DOUBLE_EQ(inside.hit_fraction, 1.0);
  EXPECT_NEAR(inside.clearance_m, 0.4, 0.4 * 0.03);  // nearest face (z = 0) is 0.4 m away

  // Above the floor beside the box: open upwards, front faces only.
  const PointProbe outside = caster.Probe(Eigen::Vector3d(3, 3, 0.5));
  EXPECT_FALSE(outside.inside);
  EXPECT_DOUBLE_EQ(outside.back_face_fraction, 0.0);
  EXPECT_NEAR(outside.clearance_m, 1.5, 1.5 * 0.03);
}

TEST(RaycasterTest, FibonacciDirectionsAreUnitEvenAndSpreadOverTheSphere) {
  const std::vector<Eigen::Vector3f> d = FibonacciDirections(256);
  ASSERT_EQ(d.size(), 256u);
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  int upper = 0;
  for (const auto& v : d) {
    EXPECT_NEAR(v.norm(), 1.f, 1e-5f);
    sum += v;
    upper += v.z() > 0.f ? 1 : 0;
  }
  EXPECT_EQ(upper, 128);                 // z runs evenly from +1 to -1
  EXPECT_LT(sum.norm() / 256.f, 0.01f);  // no direction favoured
  EXPECT_GT(d.front().z(), 0.99f);
  EXPECT_TRUE(FibonacciDirections(0).empty());
}

}  // namespace
}  // namespace objscan::render
