#include "objscan/geometry/mesh_decimation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <tuple>
#include <unordered_map>

namespace objscan::geometry {

namespace {

bool ValidTriangle(const Eigen::Vector3i& t, int num_vertices) {
  return (t.array() >= 0).all() && (t.array() < num_vertices).all();
}

// The mesh without unreferenced vertices nor triangles with an out-of-range index; vertices in the
// order the triangles first use them.
TriangleMesh Compacted(const TriangleMesh& mesh) {
  const int n = static_cast<int>(mesh.vertices.size());
  std::vector<int> new_index(mesh.vertices.size(), -1);
  TriangleMesh out;
  out.triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    if (!ValidTriangle(t, n)) continue;
    Eigen::Vector3i u;
    for (int k = 0; k < 3; ++k) {
      int& j = new_index[static_cast<std::size_t>(t[k])];
      if (j < 0) {
        j = static_cast<int>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[static_cast<std::size_t>(t[k])]);
      }
      u[k] = j;
    }
    out.triangles.push_back(u);
  }
  return out;
}

}  // namespace

TriangleMesh ClusterVertices(const TriangleMesh& mesh, double cell_m) {
  const int n = static_cast<int>(mesh.vertices.size());
  // The grid is anchored at the minimum corner of the referenced, finite vertices.
  Aabb3 box;
  for (const auto& t : mesh.triangles) {
    if (!ValidTriangle(t, n)) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3f& v = mesh.vertices[static_cast<std::size_t>(t[k])];
      if (v.allFinite()) box.Extend(v.cast<double>());
    }
  }
  TriangleMesh out;
  if (box.Empty() || !(cell_m > 0.0)) return out;
  // Cell coordinates in 21 bits each (a key of 63 bits): a coarser grid for a mesh that would need more.
  constexpr double kMaxCells = double((1 << 21) - 1);
  cell_m = std::max(cell_m, box.Size().maxCoeff() / kMaxCells);

  std::unordered_map<std::uint64_t, int> cluster_of_key;
  std::vector<int> cluster_of_vertex(mesh.vertices.size(), -1);
  std::vector<Eigen::Vector3d> sum;
  std::vector<int> count;
  const auto cluster = [&](int i) {
    int& c = cluster_of_vertex[static_cast<std::size_t>(i)];
    if (c >= 0) return c;
    const Eigen::Vector3d p = mesh.vertices[static_cast<std::size_t>(i)].cast<double>();
    std::uint64_t key = 0;
    for (int a = 0; a < 3; ++a) {
      const double cell = std::clamp(std::floor((p[a] - box.min_m[a]) / cell_m), 0.0, kMaxCells);
      key = (key << 21) | static_cast<std::uint64_t>(cell);
    }
    const auto [it, added] = cluster_of_key.emplace(key, static_cast<int>(sum.size()));
    if (added) {
      sum.push_back(Eigen::Vector3d::Zero());
      count.push_back(0);
    }
    c = it->second;
    sum[static_cast<std::size_t>(c)] += p;
    ++count[static_cast<std::size_t>(c)];
    return c;
  };
  // Triangles of three distinct clusters, each once (the same corners in the same turn; a face and
  // its back face both stay).
  std::set<std::tuple<int, int, int>> seen;
  for (const auto& t : mesh.triangles) {
    if (!ValidTriangle(t, n)) continue;
    bool finite = true;
    for (int k = 0; k < 3; ++k) finite = finite && mesh.vertices[static_cast<std::size_t>(t[k])].allFinite();
    if (!finite) continue;
    const int a = cluster(t[0]), b = cluster(t[1]), c = cluster(t[2]);
    if (a == b || b == c || a == c) continue;
    // Rotated so the smallest index comes first (the turn is kept).
    std::tuple<int, int, int> key = a < b && a < c ? std::make_tuple(a, b, c)
                                    : b < c       ? std::make_tuple(b, c, a)
                                                  : std::make_tuple(c, a, b);
    if (!seen.insert(key).second) continue;
    out.triangles.emplace_back(a, b, c);
  }
  out.vertices.resize(sum.size());
  for (std::size_t c = 0; c < sum.size(); ++c) out.vertices[c] = (sum[c] / count[c]).cast<float>();
  // Clusters used only by vanished triangles are dropped.
  return Compacted(out);
}

BoundedMesh DecimateToTriangleBudget(const TriangleMesh& mesh, int max_triangles, double min_cell_m) {
  BoundedMesh result;
  result.mesh = Compacted(mesh);
  const std::size_t budget = static_cast<std::size_t>(std::max(0, max_triangles));
  if (result.mesh.triangles.size() <= budget) return result;
  const TriangleMesh source = std::move(result.mesh);
  // A mesh thin in two directions (a pencil, a pole) collapses to a line on a grid coarser than its
  // width: the grid starts finer than a quarter of the second-smallest extent.
  Eigen::Vector3d extent = Bounds(source).Size();
  std::sort(extent.data(), extent.data() + 3);
  double cell_m = std::max(min_cell_m, 1e-6);
  if (extent[1] > 0.0) cell_m = std::max(std::min(cell_m, extent[1] / 4.0), 1e-6);
  for (;;) {
    result.mesh = ClusterVertices(source, cell_m);
    result.cell_m = cell_m;
    if (result.mesh.triangles.size() <= budget) break;
    cell_m *= 1.25;
  }
  if (result.mesh.Empty() && budget > 0) {
    // Collapsed from above the budget to nothing in one step: every k-th triangle of the mesh instead
    // (a coarse but bounded stand-in that keeps the shape's extent roughly).
    const std::size_t stride = (source.triangles.size() + budget - 1) / budget;
    TriangleMesh sampled;
    sampled.vertices = source.vertices;
    for (std::size_t t = 0; t < source.triangles.size(); t += stride) sampled.triangles.push_back(source.triangles[t]);
    result.mesh = Compacted(sampled);
    result.cell_m = 0.0;
  }
  return result;
}

}  // namespace objscan::geometry
