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

VoxelOccupancy VoxelOccupancy::Of(int nx, int ny, int nz, const std::uint16_t* mask,
                                  const std::uint8_t* free_distance) {
  VoxelOccupancy g;
  g.nx = nx;
  g.ny = ny;
  g.nz = nz;
  g.mask = mask;
  g.free_distance = free_distance;
  int lo[3] = {nx, ny, nz}, hi[3] = {0, 0, 0};
  std::size_t i = 0;
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x, ++i) {
        if (mask[i] == 0) continue;
        const int c[3] = {x, y, z};
        for (int a = 0; a < 3; ++a) {
          lo[a] = std::min(lo[a], c[a]);
          hi[a] = std::max(hi[a], c[a] + 1);
        }
      }
    }
  }
  for (int a = 0; a < 3; ++a) {
    g.box_min[a] = lo[a];
    g.box_max[a] = std::max(lo[a], hi[a]);
  }
  return g;
}

std::uint16_t BlockingBits(const VoxelOccupancy& grid, const Eigen::Vector3d& eye_grid, int tx, int ty, int tz,
                           double tolerance_voxels, std::uint16_t stop_any, std::uint16_t stop_all) {
  const Eigen::Vector3d target(tx + 0.5, ty + 0.5, tz + 0.5);
  const Eigen::Vector3d d = target - eye_grid;
  const double length = d.norm();
  if (length <= tolerance_voxels || !eye_grid.allFinite()) return 0;
  const std::ptrdiff_t stride[3] = {1, static_cast<std::ptrdiff_t>(grid.nx),
                                    static_cast<std::ptrdiff_t>(grid.nx) * static_cast<std::ptrdiff_t>(grid.ny)};
  // A large finite stand-in for infinity: multiplied by 0 in the branch-free step below it stays 0.
  constexpr double kNever = 1e300;
  int step[3];
  double inv[3], t_delta[3];
  std::ptrdiff_t index_step[3];
  double d_inf = 0.0;
  for (int a = 0; a < 3; ++a) {
    step[a] = d[a] > 0.0 ? 1 : (d[a] < 0.0 ? -1 : 0);
    inv[a] = d[a] != 0.0 ? 1.0 / d[a] : 0.0;
    t_delta[a] = d[a] != 0.0 ? std::abs(inv[a]) : kNever;
    index_step[a] = step[a] * stride[a];
    d_inf = std::max(d_inf, std::abs(d[a]));
  }
  // Only the part of the segment inside the box of occupied voxels can meet anything.
  double t = 0.0;
  double t_end = 1.0 - tolerance_voxels / length;
  for (int a = 0; a < 3; ++a) {
    if (step[a] == 0) {
      if (eye_grid[a] < grid.box_min[a] || eye_grid[a] > grid.box_max[a]) return 0;
      continue;
    }
    const double t_lo = (grid.box_min[a] - eye_grid[a]) * inv[a];
    const double t_hi = (grid.box_max[a] - eye_grid[a]) * inv[a];
    t = std::max(t, std::min(t_lo, t_hi));
    t_end = std::min(t_end, std::max(t_lo, t_hi));
  }
  if (t >= t_end) return 0;
  const double inv_d_inf = 1.0 / d_inf;
  int cell[3];
  double t_max[3];
  std::ptrdiff_t index = 0;
  // (Re)starts the DDA at parameter t: the voxel holding that point and the next boundary per axis.
  auto start_at = [&](double t_start) {
    index = 0;
    for (int a = 0; a < 3; ++a) {
      const double p = eye_grid[a] + t_start * d[a];
      cell[a] = std::min(grid.box_max[a] - 1, std::max(grid.box_min[a], static_cast<int>(std::floor(p))));
      t_max[a] = step[a] > 0 ? (cell[a] + 1 - eye_grid[a]) * inv[a]
                             : (step[a] < 0 ? (cell[a] - eye_grid[a]) * inv[a] : kNever);
      index += cell[a] * stride[a];
    }
  };
  start_at(t);
  const std::ptrdiff_t target_index = tx + stride[1] * ty + stride[2] * tz;
  const unsigned box_size[3] = {static_cast<unsigned>(grid.box_max[0] - grid.box_min[0]),
                                static_cast<unsigned>(grid.box_max[1] - grid.box_min[1]),
                                static_cast<unsigned>(grid.box_max[2] - grid.box_min[2])};
  std::uint16_t bits = 0;
  while (t < t_end && index != target_index) {
    bits |= grid.mask[index];
    if ((bits & stop_any) != 0 || (bits & stop_all) == stop_all) break;
    if (grid.free_distance != nullptr && grid.free_distance[index] >= 2) {
      // The point at t lies in this voxel; every voxel within k - 1 of it per axis is empty, and a move
      // of (k - 1) / |d|_inf in t moves at most k - 1 voxels along any axis.
      t += (grid.free_distance[index] - 1) * inv_d_inf;
      if (t >= t_end) break;
      start_at(t);
      continue;
    }
    // Branch-free step to the next voxel: the axis whose boundary comes first (ties: x, then y).
    const int sx = t_max[0] <= t_max[1] && t_max[0] <= t_max[2];
    const int sy = !sx && t_max[1] <= t_max[2];
    const int sz = !sx && !sy;
    t = std::min(t_max[0], std::min(t_max[1], t_max[2]));
    cell[0] += sx * step[0];
    cell[1] += sy * step[1];
    cell[2] += sz * step[2];
    index += sx * index_step[0] + sy * index_step[1] + sz * index_step[2];
    t_max[0] += sx * t_delta[0];
    t_max[1] += sy * t_delta[1];
    t_max[2] += sz * t_delta[2];
    // Leaving the box: nothing occupied lies further on.
    if (static_cast<unsigned>(cell[0] - grid.box_min[0]) >= box_size[0] ||
        static_cast<unsigned>(cell[1] - grid.box_min[1]) >= box_size[1] ||
        static_cast<unsigned>(cell[2] - grid.box_min[2]) >= box_size[2]) {
      break;
    }
  }
  return bits;
}

void ChebyshevFreeDistance(int nx, int ny, int nz, const std::uint16_t* mask, std::vector<std::uint8_t>* distance) {
  // Two raster passes of the 3x3x3 chamfer with unit weights (exact for the chessboard metric), on a
  // copy padded by one voxel of "far" so the 13 neighbours need no bounds checks.
  const int px = nx + 2, py = ny + 2, pz = nz + 2;
  const std::ptrdiff_t sy = px, sz = static_cast<std::ptrdiff_t>(px) * py;
  std::vector<std::uint8_t> padded(static_cast<std::size_t>(px) * py * pz, 255);
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      const std::uint16_t* m = mask + static_cast<std::size_t>(nx) * (y + static_cast<std::size_t>(ny) * z);
      std::uint8_t* d = padded.data() + (z + 1) * sz + (y + 1) * sy + 1;
      for (int x = 0; x < nx; ++x) d[x] = m[x] != 0 ? 0 : 255;
    }
  }
  // Offsets of the 13 neighbours that precede a voxel in raster order (x fastest); the backward pass
  // uses their negatives.
  std::ptrdiff_t before[13];
  int count = 0;
  for (int dz = -1; dz <= 0; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dz < 0 || dy < 0 || (dy == 0 && dx < 0)) before[count++] = dz * sz + dy * sy + dx;
  std::uint8_t* base = padded.data();
  auto relax = [&](std::ptrdiff_t i, int sign) {
    int best = base[i];
    if (best == 0) return;
    for (int k = 0; k < 13; ++k) best = std::min(best, base[i + sign * before[k]] + 1);
    base[i] = static_cast<std::uint8_t>(std::min(best, 255));
  };
  for (int z = 1; z <= nz; ++z)
    for (int y = 1; y <= ny; ++y)
      for (std::ptrdiff_t i = z * sz + y * sy + 1, end = i + nx; i < end; ++i) relax(i, 1);
  for (int z = nz; z >= 1; --z)
    for (int y = ny; y >= 1; --y)
      for (std::ptrdiff_t i = z * sz + y * sy + nx, end = i - nx; i > end; --i) relax(i, -1);
  distance->resize(static_cast<std::size_t>(nx) * ny * nz);
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      const std::uint8_t* d = padded.data() + (z + 1) * sz + (y + 1) * sy + 1;
      std::copy(d, d + nx, distance->data() + static_cast<std::size_t>(nx) * (y + static_cast<std::size_t>(ny) * z));
    }
  }
}

bool IsVoxelVisible(int nx, int ny, int nz, const std::uint16_t* mask, std::uint16_t blocking_bits,
                    const Eigen::Vector3d& eye_grid, int tx, int ty, int tz, double tolerance_voxels) {
  VoxelOccupancy grid;
  grid.nx = nx;
  grid.ny = ny;
  grid.nz = nz;
  grid.mask = mask;
  grid.box_max[0] = nx;  // the whole grid: no scan needed for a single ray
  grid.box_max[1] = ny;
  grid.box_max[2] = nz;
  return (BlockingBits(grid, eye_grid, tx, ty, tz, tolerance_voxels, blocking_bits, 0xFFFF) & blocking_bits) == 0;
}

}  // namespace objscan::planning
