#pragma once
// Indexed triangle mesh (float vertices in metres). Plain data; algorithms are free functions.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "objscan/geometry/aabb.h"

namespace objscan::geometry {

struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;

  bool Empty() const { return triangles.empty(); }
  std::size_t NumTriangles() const { return triangles.size(); }
};

Aabb3 Bounds(const TriangleMesh& mesh);
// Bounds of the mesh after transforming it by T.
Aabb3 Bounds(const TriangleMesh& mesh, const Eigen::Isometry3d& T);
TriangleMesh Transformed(const TriangleMesh& mesh, const Eigen::Affine3d& T);
// Appends `other` (indices offset) to `mesh`.
void Append(const TriangleMesh& other, TriangleMesh* mesh);
double SurfaceArea(const TriangleMesh& mesh);
// Drops triangles with out-of-range indices or zero area and unreferenced vertices are kept.
// Returns the number of triangles removed.
std::size_t RemoveDegenerateTriangles(TriangleMesh* mesh);

// Primitives (outward-facing triangles, centred on the origin unless stated).
TriangleMesh MakeBox(const Eigen::Vector3d& size_m);
// Box spanning [min, max].
TriangleMesh MakeBox(const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m);
// Cylinder along Z, centred on the origin.
TriangleMesh MakeCylinder(double radius_m, double length_m, int segments = 24);
TriangleMesh MakeSphere(double radius_m, int segments = 16);
// Flat quad in the plane z = 0 spanning [x0,x1]x[y0,y1], normal +Z.
TriangleMesh MakeQuadXY(double x0, double y0, double x1, double y1);

}  // namespace objscan::geometry
