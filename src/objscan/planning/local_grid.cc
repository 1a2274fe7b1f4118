#include "objscan/planning/local_grid.h"

#include <algorithm>

namespace objscan::planning {

LocalGrid LocalGrid::Covering(const geometry::Aabb3& box, double voxel_size_m, double padding_m,
                              std::size_t max_voxels) {
  LocalGrid grid;
  if (box.Empty()) return grid;
  const Eigen::Vector3d lo = box.min_m - Eigen::Vector3d::Constant(padding_m);
  const Eigen::Vector3d extent = box.Size() + Eigen::Vector3d::Constant(2.0 * padding_m);
  double v = voxel_size_m;
  for (;;) {
    const Eigen::Vector3d n = (extent / v).array().ceil().max(1.0);
    const double count = n.x() * n.y() * n.z();
    // Voxel coordinates are stored as 16-bit integers downstream.
    const bool fits_axes = n.maxCoeff() <= 32767.0;
    if (fits_axes && (count <= static_cast<double>(max_voxels) || max_voxels == 0)) {
      grid.nx = static_cast<int>(n.x());
      grid.ny = static_cast<int>(n.y());
      grid.nz = static_cast<int>(n.z());
      break;
    }
    // Coarsen by the cube root of the excess (plus a hair so rounding cannot loop).
    const double over_budget = max_voxels > 0 ? std::cbrt(count / static_cast<double>(max_voxels)) : 1.0;
    v *= std::max(over_budget, n.maxCoeff() / 32767.0) * 1.001;
  }
  grid.voxel_size_m = v;
  // Centre the block on the box so the padding is the same on both sides.
  const Eigen::Vector3d span(grid.nx * v, grid.ny * v, grid.nz * v);
  grid.origin_world = lo - 0.5 * (span - extent);
  return grid;
}

void RasterizeIndicator(const LocalGrid& grid, const std::vector<Eigen::Vector3f>& points_world,
                        std::vector<float>* field) {
  int x, y, z;
  for (const Eigen::Vector3f& p : points_world) {
    if (grid.VoxelOf(p, &x, &y, &z)) (*field)[grid.Index(x, y, z)] = 1.0f;
  }
}

void RasterizeMask(const LocalGrid& grid, const std::vector<Eigen::Vector3f>& points_world, std::uint16_t bits,
                   std::vector<std::uint16_t>* mask) {
  int x, y, z;
  for (const Eigen::Vector3f& p : points_world) {
    if (grid.VoxelOf(p, &x, &y, &z)) (*mask)[grid.Index(x, y, z)] |= bits;
  }
}

void RasterizeIndicatorAndMask(const LocalGrid& grid, const std::vector<Eigen::Vector3f>& points_world,
                               std::vector<float>* field, std::uint16_t bits, std::vector<std::uint16_t>* mask) {
  int x, y, z;
  for (const Eigen::Vector3f& p : points_world) {
    if (!grid.VoxelOf(p, &x, &y, &z)) continue;
    const std::size_t i = grid.Index(x, y, z);
    if (field != nullptr) (*field)[i] = 1.0f;
    (*mask)[i] |= bits;
  }
}

}  // namespace objscan::planning
