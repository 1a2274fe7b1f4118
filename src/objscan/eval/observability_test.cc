#include "objscan/eval/observability.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"
#include "objscan/eval/exposure.h"
#include "objscan/render/raycaster.h"
#include "objscan/sim/test_scenes.h"

namespace objscan::eval {
namespace {

using sim::testing::BoxObject;
using sim::testing::Room;

NormalLines Line(double x, double y, double z) { return {Eigen::Vector3f(x, y, z)}; }

// Robot camera heights over the test rooms' floor (z = 0).
ObservabilityOptions RobotCamera() {
  ObservabilityOptions o;
  o.min_range_m = 0.5;
  o.max_range_m = 4.0;
  o.max_incidence_deg = 75.0;
  o.min_camera_z_m = 0.3;
  o.max_camera_z_m = 1.8;
  o.own_surface_m = 0.045;
  o.threads = 1;
  return o;
}

// A 0.6 m high box whose -x face stands `slit_m` from the room's wall at x = 0.
world::Scene BoxBesideWall(double slit_m) {
  world::Scene scene = Room(3.0, 3.0);
  scene.Add(BoxObject({slit_m, 1.0, 0.0}, {slit_m + 0.6, 2.0, 0.6}));
  return scene;
}

// With dropout at 75 degrees, a line of sight from a face in a slit of width g runs at most
// g / cos(75) = 3.86 g before it meets the wall: under 0.5 m (min range) when g < 0.13 m.
TEST(ObservableVoxels, AFaceInASlitBesideTheWallIsNotObservableItsFrontIs) {
  const world::Scene scene = BoxBesideWall(0.08);
  const render::Raycaster caster(scene.BuildTriangleSoup());
  const std::vector<Eigen::Vector3d> centers = {{0.08, 1.5, 0.3}, {0.68, 1.5, 0.3}, {0.38, 1.5, 0.6}};
  const std::vector<NormalLines> lines = {Line(-1, 0, 0), Line(1, 0, 0), Line(0, 0, 1)};
  const std::vector<char> observable = ObservableVoxels(caster, centers, lines, RobotCamera());
  ASSERT_EQ(observable.size(), 3u);
  EXPECT_EQ(observable[0], 0) << "the slit face";
  EXPECT_EQ(observable[1], 1) << "the face towards the room";
  EXPECT_EQ(observable[2], 1) << "the top";
}

TEST(ObservableVoxels, AFaceThirtyCentimetresFromTheWallIsObservableObliquely) {
  // g = 0.3: a ray 60 degrees off the face's normal, upwards, runs 0.6 m before the wall.
  const world::Scene scene = BoxBesideWall(0.30);
  const render::Raycaster caster(scene.BuildTriangleSoup());
  const std::vector<char> observable = ObservableVoxels(caster, {{0.30, 1.5, 0.3}}, {Line(-1, 0, 0)}, RobotCamera());
  EXPECT_EQ(observable[0], 1);
}

TEST(ObservableVoxels, RaysRunningInsideASolidDoNotCount) {
  // A normal wound the wrong way sends the rays into a 0.6 m box standing clear of the floor: its
  // far side is beyond min range, but the first hit there is a back face.
  world::Scene scene = Room(3.0, 3.0);
  scene.Add(BoxObject({1.0, 1.0, 0.3}, {1.6, 1.6, 0.9}));
  const render::Raycaster caster(scene.BuildTriangleSoup());
  ObservabilityOptions o = RobotCamera();
  o.min_camera_z_m = -10.0;
  o.max_camera_z_m = 10.0;
  EXPECT_EQ(ObservableVoxels(caster, {{1.0, 1.3, 0.6}}, {Line(1, 0, 0)}, o)[0], 0);
  EXPECT_EQ(ObservableVoxels(caster, {{1.0, 1.3, 0.6}}, {Line(-1, 0, 0)}, o)[0], 1);
}

TEST(ObservableVoxels, TheTopOfAWardrobeAboveTheHighestCameraIsNotObservable) {
  world::Scene scene = Room(4.0, 4.0);
  scene.Add(BoxObject({1.5, 1.5, 0.0}, {2.1, 2.5, 2.2}));
  const render::Raycaster caster(scene.BuildTriangleSoup());
  const std::vector<Eigen::Vector3d> top = {{1.8, 2.0, 2.2}};
  EXPECT_EQ(ObservableVoxels(caster, top, {Line(0, 0, 1)}, RobotCamera())[0], 0);
  ObservabilityOptions any_height = RobotCamera();
  any_height.min_camera_z_m = -std::numeric_limits<double>::infinity();
  any_height.max_camera_z_m = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ObservableVoxels(caster, top, {Line(0, 0, 1)}, any_height)[0], 1);
  // A camera at 1.8 m sees the top of a 1.6 m cabinet obliquely (a ray 75 degrees off vertical
  // climbs 0.13 m per 0.5 m).
  world::Scene low = Room(4.0, 4.0);
  low.Add(BoxObject({1.5, 1.5, 0.0}, {2.1, 2.5, 1.6}));
  const render::Raycaster low_caster(low.BuildTriangleSoup());
  EXPECT_EQ(ObservableVoxels(low_caster, {{1.8, 2.0, 1.6}}, {Line(0, 0, 1)}, RobotCamera())[0], 1);
}

TEST(ObservableVoxels, WithTheRoomsAirTheCameraMustBeInsideTheRoom) {
  // The outer face of a box beyond the wall at x = 3.1 has free lines of sight, all outside.
  world::Scene scene = Room(3.0, 3.0);
  scene.Add(BoxObject({3.3, 1.0, 0.5}, {3.6, 2.0, 1.5}));
  scene.Add(BoxObject({1.0, 1.0, 0.0}, {1.6, 1.6, 0.6}));
  const render::Raycaster caster(scene.BuildTriangleSoup());
  const RoomAir air(scene, 0.05, Eigen::Vector3d(0.5, 0.5, 1.0));
  const std::vector<Eigen::Vector3d> centers = {{3.6, 1.5, 1.0}, {1.6, 1.3, 0.3}};
  const std::vector<NormalLines> lines = {Line(1, 0, 0), Line(1, 0, 0)};
  EXPECT_EQ(ObservableVoxels(caster, centers, lines, RobotCamera()), (std::vector<char>{1, 1}));
  EXPECT_EQ(ObservableVoxels(caster, centers, lines, RobotCamera(), &air), (std::vector<char>{0, 1}));
}

TEST(ObservableVoxels, OneOfSeveralOrientationsSuffices) {
  // A voxel in the slit holding the hidden face and a horizontal ledge: a camera above the slit
  // looks down on the ledge.
  const world::Scene scene = BoxBesideWall(0.08);
  const render::Raycaster caster(scene.BuildTriangleSoup());
  NormalLines both = {Eigen::Vector3f(-1, 0, 0)};
  EXPECT_EQ(ObservableVoxels(caster, {{0.08, 1.5, 0.3}}, {both}, RobotCamera())[0], 0);
  both.push_back(Eigen::Vector3f(0, 0, 1));
  EXPECT_EQ(ObservableVoxels(caster, {{0.08, 1.5, 0.3}}, {both}, RobotCamera())[0], 1);
  // No orientation known: kept.
  EXPECT_EQ(ObservableVoxels(caster, {{0.08, 1.5, 0.3}}, {NormalLines{}}, RobotCamera())[0], 1);
}

TEST(ObservableVoxels, ResultsDoNotDependOnTheThreadCount) {
  const world::Scene scene = BoxBesideWall(0.12);
  const render::Raycaster caster(scene.BuildTriangleSoup());
  std::vector<Eigen::Vector3d> centers;
  std::vector<NormalLines> lines;
  for (int i = 0; i < 600; ++i) {
    // Every third voxel on the face towards the room, the others on the slit face.
    const bool front = i % 3 == 0;
    centers.emplace_back(front ? 0.72 : 0.12, 1.05 + 0.9 * i / 600.0, 0.05 + 0.5 * ((i * 7) % 10) / 10.0);
    lines.push_back(Line(front ? 1 : -1, 0, 0));
  }
  ObservabilityOptions one = RobotCamera(), many = RobotCamera();
  many.threads = 4;
  const std::vector<char> a = ObservableVoxels(caster, centers, lines, one);
  EXPECT_EQ(a, ObservableVoxels(caster, centers, lines, many));
  EXPECT_EQ(std::count(a.begin(), a.end(), 1), 200);
}

TEST(ObservableVoxels, RejectsMismatchedSizesAndBadOptions) {
  const world::Scene scene = BoxBesideWall(0.3);
  const render::Raycaster caster(scene.BuildTriangleSoup());
  EXPECT_THROW(ObservableVoxels(caster, {{0.3, 1.5, 0.3}}, {}, RobotCamera()), InputError);
  ObservabilityOptions o = RobotCamera();
  o.max_incidence_deg = 0.0;
  EXPECT_THROW(ObservableVoxels(caster, {}, {}, o), InputError);
  o = RobotCamera();
  o.max_range_m = 0.4;
  EXPECT_THROW(ObservableVoxels(caster, {}, {}, o), InputError);
  o = RobotCamera();
  o.min_camera_z_m = std::nan("");
  EXPECT_THROW(ObservableVoxels(caster, {}, {}, o), InputError);
}

TEST(AddNormalLine, MergesNearNormalsKeepsOppositeAndPerpendicularOnesApart) {
  NormalLines lines;
  AddNormalLine(&lines, Eigen::Vector3f(1, 0, 0), 1.f);
  AddNormalLine(&lines, Eigen::Vector3f(-1, 0, 0), 1.f);  // the other face of a thin panel
  AddNormalLine(&lines, Eigen::Vector3f(0.95f, 0.3122f, 0), 1.f);  // 18 degrees off the first
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_GT(lines[0].x(), 1.9f);
  EXPECT_FLOAT_EQ(lines[1].x(), -1.f);
  AddNormalLine(&lines, Eigen::Vector3f(0, 0, 1), 1.f);
  EXPECT_EQ(lines.size(), 3u);
  AddNormalLine(&lines, Eigen::Vector3f(0, 1, 0), 0.f);  // no area: ignored
  EXPECT_EQ(lines.size(), 3u);
  AddNormalLine(&lines, Eigen::Vector3f(0, 1, 0), 1.f, 25.0, 3);  // full: into the closest line
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_GT(lines[0].y(), 1.3f);
}

}  // namespace
}  // namespace objscan::eval
