#pragma once
// 3-D DDA voxel traversal (Amanatides & Woo 1987) over a dense grid, in continuous grid coordinates
// (voxel (i, j, k) spans [i, i+1) x [j, j+1) x [k, k+1)). Used for the NBV visibility g(x, V).
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace objscan::planning {

// Visits, in order, every voxel of an nx x ny x nz grid crossed by the segment p0 -> p1 (clipped to the
// grid). t_enter() is the segment parameter in [0, 1] at which the current voxel is entered.
class VoxelWalker {
 public:
  VoxelWalker(int nx, int ny, int nz, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1);

  bool Done() const { return done_; }
  int x() const { return cell_[0]; }
  int y() const { return cell_[1]; }
  int z() const { return cell_[2]; }
  std::size_t index() const { return index_; }  // x + nx * (y + ny * z)
  double t_enter() const { return t_enter_; }
  void Next() {
    const int a = t_max_[0] < t_max_[1] ? (t_max_[0] < t_max_[2] ? 0 : 2) : (t_max_[1] < t_max_[2] ? 1 : 2);
    t_enter_ = t_max_[a];
    if (t_enter_ >= t_end_) {
      done_ = true;
      return;
    }
    cell_[a] += step_[a];
    if (cell_[a] < 0 || cell_[a] >= size_[a]) {
      done_ = true;
      return;
    }
    index_ = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(index_) + index_step_[a]);
    t_max_[a] += t_delta_[a];
  }

 private:
  int size_[3];
  int cell_[3] = {0, 0, 0};
  int step_[3] = {0, 0, 0};
  std::ptrdiff_t index_step_[3] = {0, 0, 0};
  double t_max_[3];
  double t_delta_[3];
  double t_enter_ = 0.0;
  double t_end_ = 0.0;
  std::size_t index_ = 0;
  bool done_ = true;
};

// g(x, V): true when no voxel with (mask & blocking_bits) != 0 lies on the segment from `eye_grid` to the
// centre of voxel (tx, ty, tz), ignoring the target voxel itself and every voxel entered within the last
// `tolerance_voxels` of the path (so a surface does not hide itself at grazing angles through its own
// neighbouring voxels). Parts of the path outside the grid are not checked.
bool IsVoxelVisible(int nx, int ny, int nz, const std::uint16_t* mask, std::uint16_t blocking_bits,
                    const Eigen::Vector3d& eye_grid, int tx, int ty, int tz, double tolerance_voxels);

// A grid of occupancy bit masks as the ray walks see it.
struct VoxelOccupancy {
  int nx = 0, ny = 0, nz = 0;
  const std::uint16_t* mask = nullptr;
  const std::uint8_t* free_distance = nullptr;  // ChebyshevFreeDistance of mask, or null
  // Voxel range [box_min, box_max) holding every voxel with a non-zero mask; walks are clipped to it.
  int box_min[3] = {0, 0, 0};
  int box_max[3] = {0, 0, 0};

  // Fills the box from the mask (empty when no voxel is set).
  static VoxelOccupancy Of(int nx, int ny, int nz, const std::uint16_t* mask, const std::uint8_t* free_distance);
};

// The same walk for several occupancy layers at once: the OR of the mask bits of the voxels that
// IsVoxelVisible would check. The walk stops early once a bit of `stop_any` or all bits of `stop_all`
// have been met, since the caller's answer cannot change after that (stop_all must not be 0). With a
// free-distance field the walk leaps over empty space instead of stepping voxel by voxel, with the
// same result.
std::uint16_t BlockingBits(const VoxelOccupancy& grid, const Eigen::Vector3d& eye_grid, int tx, int ty, int tz,
                           double tolerance_voxels, std::uint16_t stop_any, std::uint16_t stop_all);

// Per voxel, the chessboard (L-infinity) distance in voxels to the nearest voxel with a non-zero mask
// (0 on such voxels), capped at 255; voxels outside the grid do not count. Every voxel closer than that
// to v in all three axes is empty, which is what lets a ray leap.
void ChebyshevFreeDistance(int nx, int ny, int nz, const std::uint16_t* mask, std::vector<std::uint8_t>* distance);

}  // namespace objscan::planning
