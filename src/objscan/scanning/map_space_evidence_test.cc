#include "objscan/scanning/map_space_evidence.h"

#include <cmath>

#include <gtest/gtest.h>

#include "objscan/common/error.h"

namespace objscan::scanning {
namespace {

using mapping::Occupancy;

// A 10 x 10 x 10 snapshot of 0.1 m voxels from the origin: free everywhere but one occupied voxel
// (5, 5, 5) and an unknown slab x >= 8. Floor at z = 0; one wall at x = 0.9 facing -x (into the room),
// spanning y in [0, 1], z in [0, 1].
MapSpaceEvidence Evidence(const MapSpaceEvidenceOptions& options = {}) {
  mapping::OccupancySnapshot snap;
  snap.voxel_size_m = 0.1;
  snap.nx = snap.ny = snap.nz = 10;
  snap.cells.assign(1000, Occupancy::kFree);
  snap.cells[snap.Index(5, 5, 5)] = Occupancy::kOccupied;
  for (int z = 0; z < 10; ++z)
    for (int y = 0; y < 10; ++y)
      for (int x = 8; x < 10; ++x) snap.cells[snap.Index(x, y, z)] = Occupancy::kUnknown;
  mapping::StructureResult structure;
  structure.has_floor = true;
  structure.floor_height_m = 0.0;
  mapping::WallPlane wall;
  wall.normal = Eigen::Vector3d(-1, 0, 0);
  wall.offset_m = -0.9;  // n . x = -0.9 at x = 0.9; room side x < 0.9
  // Along = -n.y x + n.x y = -y: the span in those units.
  wall.span_min_m = -1.0;
  wall.span_max_m = 0.0;
  wall.z_min_m = 0.0;
  wall.z_max_m = 1.0;
  structure.walls.push_back(wall);
  return MapSpaceEvidence(snap, structure, options);
}

Eigen::Vector3f Voxel(int x, int y, int z) { return Eigen::Vector3f(x + 0.5f, y + 0.5f, z + 0.5f) * 0.1f; }

TEST(MapSpaceEvidence, DeepFreeSpaceBelowTheFloorAndBehindAWallAreImpossible) {
  const MapSpaceEvidence e = Evidence();
  const Eigen::Vector3f inside(0.3f, 0.5f, 0.5f);
  EXPECT_TRUE(e.Impossible(Voxel(2, 2, 2), inside));   // free with free neighbours
  EXPECT_FALSE(e.Impossible(Voxel(5, 5, 5), inside));  // occupied
  EXPECT_FALSE(e.Impossible(Voxel(4, 5, 5), inside));  // free, next to the occupied voxel (eroded)
  EXPECT_FALSE(e.Impossible(Voxel(7, 5, 5), inside));  // free, next to unknown
  EXPECT_FALSE(e.Impossible(Voxel(8, 5, 5), inside));  // unknown, 0.05 m behind the wall
  EXPECT_FALSE(e.Impossible(Eigen::Vector3f(0.5f, 0.5f, -0.03f), inside));  // within 5 cm below the floor
  EXPECT_TRUE(e.Impossible(Eigen::Vector3f(0.5f, 0.5f, -0.08f), inside));
  EXPECT_FALSE(e.Impossible(Eigen::Vector3f(1.15f, 0.5f, 0.5f), inside));  // 0.25 m behind: a reveal
  EXPECT_TRUE(e.Impossible(Eigen::Vector3f(1.25f, 0.5f, 0.5f), inside));   // 0.35 m behind
  EXPECT_FALSE(e.Impossible(Eigen::Vector3f(1.25f, 1.5f, 0.5f), inside));  // beside the wall's span
  // A query beyond the wall (seen through a door) is not judged by it.
  EXPECT_FALSE(e.Impossible(Eigen::Vector3f(1.25f, 0.5f, 0.5f), Eigen::Vector3f(1.5f, 0.5f, 0.5f)));
  // Outside the snapshot nothing is known.
  EXPECT_FALSE(e.Impossible(Eigen::Vector3f(-0.5f, 0.5f, 0.5f), inside));
}

TEST(MapSpaceEvidence, WithoutErosionEveryFreeVoxelIsImpossibleAndFractionsCount) {
  MapSpaceEvidenceOptions options;
  options.erode_free = false;
  const MapSpaceEvidence e = Evidence(options);
  const Eigen::Vector3f inside(0.3f, 0.5f, 0.5f);
  EXPECT_TRUE(e.Impossible(Voxel(4, 5, 5), inside));
  EXPECT_TRUE(e.Impossible(Voxel(7, 5, 5), inside));
  EXPECT_DOUBLE_EQ(e.ImpossibleFraction({Voxel(4, 5, 5), Voxel(5, 5, 5), Voxel(8, 5, 5), Voxel(2, 2, 2)}, inside), 0.5);
  EXPECT_DOUBLE_EQ(e.ImpossibleFraction({}, inside), 0.0);
}

TEST(MapSpaceEvidence, DistanceToStructureIsToTheFloorOrAWallAFaceRestsAgainst) {
  MapSpaceEvidenceOptions facing;
  facing.facing_min_cos = 0.5;
  const MapSpaceEvidence e = Evidence(facing);
  // Floor z = 0; wall x = 0.9 facing -x, over y in [0, 1] and z in [0, 1]. Any face counts for the
  // floor; for the wall, faces turned to it (+x).
  const Eigen::Vector3f down(0, 0, -1), to_wall(1, 0, 0), to_room(-1, 0, 0);
  const Eigen::Vector3f both = Eigen::Vector3f(1, 0, -1).normalized();
  EXPECT_NEAR(e.SquaredDistanceToStructure({0.2f, 0.5f, 0.3f}, down), 0.09, 1e-6);
  EXPECT_NEAR(e.SquaredDistanceToStructure({0.2f, 0.5f, 0.3f}, to_room), 0.09, 1e-6);  // any face: floor
  EXPECT_NEAR(e.SquaredDistanceToStructure({0.85f, 0.5f, 0.5f}, to_wall), 0.0025, 1e-6);  // in front
  EXPECT_NEAR(e.SquaredDistanceToStructure({0.95f, 0.5f, 0.5f}, to_wall), 0.0025, 1e-6);  // behind
  // A face turned to the room: only the floor counts.
  EXPECT_NEAR(e.SquaredDistanceToStructure({0.85f, 0.5f, 0.5f}, to_room), 0.25, 1e-6);
  EXPECT_NEAR(e.SquaredDistanceToStructure({0.85f, 1.5f, 0.5f}, to_wall), 0.25, 1e-6);  // beside its span
  EXPECT_NEAR(e.SquaredDistanceToStructure({0.85f, 0.5f, 1.4f}, to_wall), 1.96, 1e-5);  // above it
  EXPECT_NEAR(e.SquaredDistanceToStructure({0.85f, 0.5f, 0.5f}, both), 0.0025, 1e-6);     // the nearer of two
  // The default, -1: any face near the wall, also one turned to the room (a window frame in its plane).
  EXPECT_NEAR(Evidence().SquaredDistanceToStructure({0.85f, 0.5f, 0.5f}, to_room), 0.0025, 1e-6);
  EXPECT_NEAR(Evidence().SquaredDistanceToStructure({0.85f, 1.5f, 0.5f}, to_room), 0.25, 1e-6);  // beside its span
  MapSpaceEvidenceOptions no_floor = facing;
  no_floor.floor_is_structure = false;
  EXPECT_TRUE(std::isinf(Evidence(no_floor).SquaredDistanceToStructure({0.2f, 0.5f, 0.3f}, down)));
  EXPECT_NEAR(Evidence(no_floor).SquaredDistanceToStructure({0.85f, 0.5f, 0.5f}, to_wall), 0.0025, 1e-6);
  const MapSpaceEvidence none(mapping::OccupancySnapshot(), mapping::StructureResult(), {});
  EXPECT_TRUE(std::isinf(none.SquaredDistanceToStructure({0.2f, 0.5f, 0.3f}, down)));
  EXPECT_EQ(none.ImpossibleFraction({Voxel(2, 2, 2)}, Eigen::Vector3f(0.3f, 0.5f, 0.5f)), 0.0);  // nothing known
}

TEST(MapSpaceEvidence, RejectsNegativeMargins) {
  MapSpaceEvidenceOptions options;
  options.behind_wall_m = -0.1;
  EXPECT_THROW(Evidence(options), InputError);
}

}  // namespace
}  // namespace objscan::scanning
