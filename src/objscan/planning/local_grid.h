#pragma once
// A small dense voxel block around one object (flat arrays, x fastest), the domain of the NBV's TDFs.
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "objscan/geometry/aabb.h"

namespace objscan::planning {

struct LocalGrid {
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();  // min corner of voxel (0, 0, 0)
  double voxel_size_m = 0.025;
  int nx = 0, ny = 0, nz = 0;

  // The grid covering `box` grown by `padding_m` on every side. When that would exceed `max_voxels` the
  // voxel size is enlarged (returned in voxel_size_m) so the grid stays within the budget (and within
  // 32767 voxels per axis).
  static LocalGrid Covering(const geometry::Aabb3& box, double voxel_size_m, double padding_m,
                            std::size_t max_voxels);

  std::size_t NumVoxels() const { return static_cast<std::size_t>(nx) * ny * nz; }
  std::size_t Index(int x, int y, int z) const {
    return static_cast<std::size_t>(x) + static_cast<std::size_t>(nx) * (static_cast<std::size_t>(y) + static_cast<std::size_t>(ny) * z);
  }
  // Voxel containing p; false when p is outside the grid (or not finite).
  bool VoxelOf(const Eigen::Vector3f& p, int* x, int* y, int* z) const {
    const double inv = 1.0 / voxel_size_m;
    const double gx = (p.x() - origin_world.x()) * inv;
    const double gy = (p.y() - origin_world.y()) * inv;
    const double gz = (p.z() - origin_world.z()) * inv;
    if (!(gx >= 0 && gy >= 0 && gz >= 0 && gx < nx && gy < ny && gz < nz)) return false;
    // Non-negative here, so truncation is floor.
    *x = static_cast<int>(gx);
    *y = static_cast<int>(gy);
    *z = static_cast<int>(gz);
    return true;
  }
  Eigen::Vector3d CenterOf(int x, int y, int z) const {
    return origin_world + voxel_size_m * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
  }
  // World point in continuous grid coordinates (voxel (i, j, k) spans [i, i + 1) x ...).
  Eigen::Vector3d ToGrid(const Eigen::Vector3d& p_world) const { return (p_world - origin_world) / voxel_size_m; }
};

// Sets field[v] = 1 for every voxel holding at least one of `points_world` (others untouched).
void RasterizeIndicator(const LocalGrid& grid, const std::vector<Eigen::Vector3f>& points_world,
                        std::vector<float>* field);
// Both at once: field[v] = 1 (when field is not null) and mask[v] |= bits.
void RasterizeIndicatorAndMask(const LocalGrid& grid, const std::vector<Eigen::Vector3f>& points_world,
                               std::vector<float>* field, std::uint16_t bits, std::vector<std::uint16_t>* mask);
// ORs `bits` into mask[v] for every voxel holding at least one point.
void RasterizeMask(const LocalGrid& grid, const std::vector<Eigen::Vector3f>& points_world, std::uint16_t bits,
                   std::vector<std::uint16_t>* mask);

}  // namespace objscan::planning
