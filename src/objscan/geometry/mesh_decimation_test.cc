#include "objscan/geometry/mesh_decimation.h"

#include <gtest/gtest.h>

namespace objscan::geometry {
namespace {

// Every side of `got` within [0, tolerance) inside `want` (clustering never grows a box).
void ExpectBoundsShrunkByLessThan(const Aabb3& got, const Aabb3& want, double tolerance_m) {
  for (int a = 0; a < 3; ++a) {
    EXPECT_GE(got.min_m[a], want.min_m[a] - 1e-6) << "axis " << a;
    EXPECT_LT(got.min_m[a], want.min_m[a] + tolerance_m) << "axis " << a;
    EXPECT_LE(got.max_m[a], want.max_m[a] + 1e-6) << "axis " << a;
    EXPECT_GT(got.max_m[a], want.max_m[a] - tolerance_m) << "axis " << a;
  }
}

TEST(MeshDecimationTest, FineSphereFitsTheBudgetAndKeepsItsBoundsWithinOneCell) {
  const TriangleMesh sphere = MakeSphere(0.4, 400);  // ~160k triangles
  ASSERT_GT(sphere.NumTriangles(), 100000u);
  const BoundedMesh decimated = DecimateToTriangleBudget(sphere, 4000, 0.01);
  EXPECT_LE(decimated.mesh.NumTriangles(), 4000u);
  // The finest grid that fits: a much smaller mesh than the budget would mean a needlessly coarse grid.
  EXPECT_GT(decimated.mesh.NumTriangles(), 4000u / 2);
  EXPECT_GE(decimated.cell_m, 0.01);
  ExpectBoundsShrunkByLessThan(Bounds(decimated.mesh), Bounds(sphere), decimated.cell_m);
  // Still a sphere: every vertex near the radius (within a cell), and most of the area kept.
  for (const auto& v : decimated.mesh.vertices) EXPECT_NEAR(v.norm(), 0.4, decimated.cell_m);
  EXPECT_NEAR(SurfaceArea(decimated.mesh), SurfaceArea(sphere), 0.1 * SurfaceArea(sphere));
  // Every index in range, no degenerate (collapsed) triangle.
  TriangleMesh copy = decimated.mesh;
  EXPECT_EQ(RemoveDegenerateTriangles(&copy), 0u);
  // Deterministic.
  const BoundedMesh again = DecimateToTriangleBudget(sphere, 4000, 0.01);
  EXPECT_EQ(again.mesh.vertices, decimated.mesh.vertices);
  EXPECT_EQ(again.mesh.triangles, decimated.mesh.triangles);
}

// A pencil (7 mm wide, 18 cm long, finely tessellated) on a 1 cm grid would collapse to a line (no
// triangle left; a Sweet Home 3D pencil did): the grid starts finer than its width.
TEST(MeshDecimationTest, ThinPencilKeepsItsShape) {
  const TriangleMesh pencil = MakeCylinder(0.0035, 0.18, 1000);
  ASSERT_GT(pencil.NumTriangles(), 3000u);
  EXPECT_TRUE(ClusterVertices(pencil, 0.01).Empty()) << "the case this guards against";
  const BoundedMesh decimated = DecimateToTriangleBudget(pencil, 3000, 0.01);
  EXPECT_LE(decimated.mesh.NumTriangles(), 3000u);
  EXPECT_GT(decimated.mesh.NumTriangles(), 24u) << "still a tube, if of fewer sides";
  EXPECT_GT(decimated.cell_m, 0.0);
  EXPECT_LE(decimated.cell_m, 0.0035);
  ExpectBoundsShrunkByLessThan(Bounds(decimated.mesh), Bounds(pencil), decimated.cell_m);
  EXPECT_NEAR(SurfaceArea(decimated.mesh), SurfaceArea(pencil), 0.2 * SurfaceArea(pencil));
}

TEST(MeshDecimationTest, SmallMeshIsKeptAsItIs) {
  TriangleMesh box = MakeBox(Eigen::Vector3d(1.0, 0.5, 0.8));
  box.vertices.push_back(Eigen::Vector3f(9.f, 9.f, 9.f));  // unreferenced: dropped
  const BoundedMesh kept = DecimateToTriangleBudget(box, 12, 0.01);
  EXPECT_EQ(kept.cell_m, 0.0);
  EXPECT_EQ(kept.mesh.NumTriangles(), 12u);
  EXPECT_EQ(kept.mesh.vertices.size(), 8u);
  ExpectBoundsShrunkByLessThan(Bounds(kept.mesh), Bounds(MakeBox(Eigen::Vector3d(1.0, 0.5, 0.8))), 1e-6);
  EXPECT_NEAR(SurfaceArea(kept.mesh), 2 * (0.5 + 0.8 + 0.4), 1e-5);
}

TEST(MeshDecimationTest, SubdividedBoxClustersBackToItsShape) {
  // A 1 x 0.6 x 0.4 m box whose faces are grids of 2 cm squares, clustered on a 5 cm grid: the
  // corners stay within a cell, the faces stay flat (every vertex within a cell of the surface).
  const Eigen::Vector3d size(1.0, 0.6, 0.4);
  TriangleMesh fine;
  const double step = 0.02;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    const int nu = static_cast<int>(std::lround(size[u] / step)), nw = static_cast<int>(std::lround(size[w] / step));
    for (int side = 0; side < 2; ++side) {
      TriangleMesh face;
      for (int i = 0; i <= nu; ++i) {
        for (int j = 0; j <= nw; ++j) {
          Eigen::Vector3f p;
          p[axis] = static_cast<float>(side ? size[axis] : 0.0);
          p[u] = static_cast<float>(i * step);
          p[w] = static_cast<float>(j * step);
          face.vertices.push_back(p);
        }
      }
      for (int i = 0; i < nu; ++i) {
        for (int j = 0; j < nw; ++j) {
          const int a = i * (nw + 1) + j, b = a + nw + 1;
          face.triangles.emplace_back(a, b, b + 1);
          face.triangles.emplace_back(a, b + 1, a + 1);
        }
      }
      Append(face, &fine);
    }
  }
  const double cell = 0.05;
  const TriangleMesh coarse = ClusterVertices(fine, cell);
  EXPECT_LT(coarse.NumTriangles(), fine.NumTriangles() / 4);
  EXPECT_GT(coarse.NumTriangles(), 12u);
  ExpectBoundsShrunkByLessThan(Bounds(coarse), Bounds(fine), cell);
  for (const auto& v : coarse.vertices) {
    // Distance to the box's surface: the smallest distance to a face plane.
    double d = 1e9;
    for (int a = 0; a < 3; ++a) d = std::min({d, std::abs(double(v[a])), std::abs(double(v[a]) - size[a])});
    EXPECT_LT(d, cell);
  }
}

TEST(MeshDecimationTest, EmptyAndBrokenMeshes) {
  EXPECT_TRUE(DecimateToTriangleBudget(TriangleMesh(), 10, 0.01).mesh.Empty());
  TriangleMesh broken;
  broken.vertices = {{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}};
  broken.triangles = {{0, 1, 2}, {0, 1, -1}};  // out of range: dropped
  EXPECT_TRUE(DecimateToTriangleBudget(broken, 10, 0.01).mesh.Empty());
  EXPECT_TRUE(ClusterVertices(broken, 0.01).Empty());
  // A budget of zero triangles gives an empty mesh (and terminates).
  EXPECT_TRUE(DecimateToTriangleBudget(MakeSphere(0.3, 16), 0, 0.01).mesh.Empty());
}

}  // namespace
}  // namespace objscan::geometry
