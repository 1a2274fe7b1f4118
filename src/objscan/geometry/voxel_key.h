#pragma once
// Integer voxel coordinates and their hash, for voxel-hashed maps.
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace objscan::geometry {

struct VoxelKey {
  std::int32_t x = 0, y = 0, z = 0;
  bool operator==(const VoxelKey& o) const { return x == o.x && y == o.y && z == o.z; }
  bool operator!=(const VoxelKey& o) const { return !(*this == o); }
  bool operator<(const VoxelKey& o) const { return x != o.x ? x < o.x : (y != o.y ? y < o.y : z < o.z); }
};

struct VoxelKeyHash {
  std::size_t operator()(const VoxelKey& k) const {
    // Large primes (Teschner et al. 2003), mixed once more for better spread in open addressing.
    std::uint64_t h = static_cast<std::uint64_t>(static_cast<std::uint32_t>(k.x)) * 73856093ull ^
                      static_cast<std::uint64_t>(static_cast<std::uint32_t>(k.y)) * 19349663ull ^
                      static_cast<std::uint64_t>(static_cast<std::uint32_t>(k.z)) * 83492791ull;
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};

// Key of the voxel containing p for voxels of size 1 / inv_voxel_size_m.
inline VoxelKey KeyOf(const Eigen::Vector3f& p, float inv_voxel_size) {
  return VoxelKey{static_cast<std::int32_t>(std::floor(p.x() * inv_voxel_size)),
                  static_cast<std::int32_t>(std::floor(p.y() * inv_voxel_size)),
                  static_cast<std::int32_t>(std::floor(p.z() * inv_voxel_size))};
}

inline Eigen::Vector3f CenterOf(const VoxelKey& k, float voxel_size) {
  return Eigen::Vector3f((k.x + 0.5f) * voxel_size, (k.y + 0.5f) * voxel_size, (k.z + 0.5f) * voxel_size);
}

}  // namespace objscan::geometry
