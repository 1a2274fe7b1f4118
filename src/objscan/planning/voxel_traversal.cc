#include "objscan/planning/voxel_traversal.h"

#include <algorithm>
#include <cmath>

namespace objscan::planning {

VoxelWalker::VoxelWalker(int nx, int ny, int nz, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) {
  size_[0] = nx;
  size_[1] = ny;
  size_[2] = nz;
  const double inf = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    t_max_[a] = inf;
    t_delta_[a] = inf;
  }
  if (nx <= 0 || ny <= 0 || nz <= 0 || !p0.allFinite() || !p1.allFinite()) return;
  const Eigen::Vector3d d = p1 - p0;
  // Clip the segment to the grid box (slab method).
  double t0 = 0.0, t1 = 1.0;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (p0[a] < 0.0 || p0[a] > size_[a]) return;
      continue;
    }
    double ta = (0.0 - p0[a]) / d[a];
    double tb = (size_[a] - p0[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1) return;
  const Eigen::Vector3d start = p0 + t0 * d;
  const std::ptrdiff_t strides[3] = {1, static_cast<std::ptrdiff_t>(nx),
                                     static_cast<std::ptrdiff_t>(nx) * static_cast<std::ptrdiff_t>(ny)};
  for (int a = 0; a < 3; ++a) {
    cell_[a] = std::min(size_[a] - 1, std::max(0, static_cast<int>(std::floor(start[a]))));
    if (d[a] > 0.0) {
      step_[a] = 1;
      t_delta_[a] = 1.0 / d[a];
      t_max_[a] = (cell_[a] + 1 - p0[a]) / d[a];
    } else if (d[a] < 0.0) {
      step_[a] = -1;
      t_delta_[a] = -1.0 / d[a];
      t_max_[a] = (cell_[a] - p0[a]) / d[a];
    }
    index_step_[a] = step_[a] * strides[a];
  }
  index_ = static_cast<std::size_t>(cell_[0] + strides[1] * cell_[1] + strides[2] * cell_[2]);
  t_enter_ = t0;
  t_end_ = t1;
  done_ = false;
}

std::uint16_t BlockingBits(int nx, int ny, int nz, const std::uint16_t* mask, const Eigen::Vector3d& eye_grid, int tx,
                           int ty, int tz, double tolerance_voxels, std::uint16_t stop_any, std::uint16_t stop_all) {
  const Eigen::Vector3d target(tx + 0.5, ty + 0.5, tz + 0.5);
  const double length = (target - eye_grid).norm();
  if (length <= tolerance_voxels) return 0;
  const double t_stop = 1.0 - tolerance_voxels / length;
  std::uint16_t bits = 0;
  for (VoxelWalker w(nx, ny, nz, eye_grid, target); !w.Done(); w.Next()) {
    if (w.t_enter() >= t_stop) break;
    if (w.x() == tx && w.y() == ty && w.z() == tz) break;
    bits |= mask[w.index()];
    if ((bits & stop_any) != 0 || (bits & stop_all) == stop_all) break;
  }
  return bits;
}

bool IsVoxelVisible(int nx, int ny, int nz, const std::uint16_t* mask, std::uint16_t blocking_bits,
                    const Eigen::Vector3d& eye_grid, int tx, int ty, int tz, double tolerance_voxels) {
  return (BlockingBits(nx, ny, nz, mask, eye_grid, tx, ty, tz, tolerance_voxels, blocking_bits, 0xFFFF) &
          blocking_bits) == 0;
}

}  // namespace objscan::planning
