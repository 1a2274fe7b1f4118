#pragma once
// Mesh decimation by vertex clustering: the vertices in each cell of a regular grid (anchored at the
// mesh's minimum corner) merge into their mean; triangles whose corners fall into fewer than three
// cells vanish, and repeated ones are dropped. Deterministic (the same mesh gives the same output,
// vertices in the order the triangles first use them) and cheap (one pass with a hash map). Every
// output vertex lies in the cell of the vertices it replaces, so the bounds shrink by less than one
// cell on every side and never grow.
#include "objscan/geometry/mesh.h"

namespace objscan::geometry {

// The mesh clustered on a grid of cells of cell_m (> 0). Unreferenced vertices are dropped.
TriangleMesh ClusterVertices(const TriangleMesh& mesh, double cell_m);

struct BoundedMesh {
  TriangleMesh mesh;
  double cell_m = 0.0;  // the grid used; 0 when the mesh was kept as it is (or sampled)
};

// The mesh with at most max_triangles (>= 0) triangles: unchanged (unreferenced vertices and
// triangles with an out-of-range index dropped) when it has that few already, else clustered on the
// finest grid of c0 * 1.25^k (k = 0, 1, ...) that brings it within the bound, where c0 is min_cell_m
// or a quarter of the mesh's second-smallest extent when that is smaller (so a thin pencil keeps its
// shape instead of collapsing to a line). Should the grid that fits leave no triangle at all, every
// k-th triangle of the mesh is kept instead (within the bound; cell_m 0).
BoundedMesh DecimateToTriangleBudget(const TriangleMesh& mesh, int max_triangles, double min_cell_m);

}  // namespace objscan::geometry
