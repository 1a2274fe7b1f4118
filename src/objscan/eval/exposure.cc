#include "objscan/eval/exposure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <string>

#include "objscan/common/error.h"

namespace objscan::eval {
namespace {

// A dense voxel grid over a box, indexed x fastest.
struct Grid {
  Eigen::Vector3i min_key = Eigen::Vector3i::Zero();
  Eigen::Vector3i size = Eigen::Vector3i::Zero();
  double inv_voxel = 1.0;

  Eigen::Vector3i KeyOf(const Eigen::Vector3d& p) const {
    return (p * inv_voxel).array().floor().cast<int>().matrix();
  }
  bool Inside(const Eigen::Vector3i& k) const {
    const Eigen::Vector3i r = k - min_key;
    return (r.array() >= 0).all() && (r.array() < size.array()).all();
  }
  std::size_t Index(const Eigen::Vector3i& k) const {
    const Eigen::Vector3i r = k - min_key;
    return (static_cast<std::size_t>(r.z()) * size.y() + r.y()) * size.x() + r.x();
  }
};

const std::array<Eigen::Vector3i, 6> kFaceNeighbours = {Eigen::Vector3i(1, 0, 0),  Eigen::Vector3i(-1, 0, 0),
                                                        Eigen::Vector3i(0, 1, 0),  Eigen::Vector3i(0, -1, 0),
                                                        Eigen::Vector3i(0, 0, 1),  Eigen::Vector3i(0, 0, -1)};

}  // namespace

std::vector<char> ExposedVoxels(const world::Scene& scene, const std::vector<Eigen::Vector3d>& voxel_centers_world,
                                double voxel_m, const Eigen::Vector3d& seed_world, const CameraHeightBand& band) {
  if (!(voxel_m > 0.0)) throw InputError("ExposedVoxels: voxel_m must be positive");
  if (std::isnan(band.min_height_m) || std::isnan(band.max_height_m) || band.min_height_m > band.max_height_m) {
    throw InputError("ExposedVoxels: the camera height band must be an interval");
  }
  std::vector<char> exposed(voxel_centers_world.size(), 0);
  const geometry::Aabb3 bounds = scene.Bounds();
  if (bounds.Empty()) return exposed;
  Grid grid;
  grid.inv_voxel = 1.0 / voxel_m;
  // Two voxels of margin so the air around the scene's outside is one connected region.
  grid.min_key = grid.KeyOf(bounds.min_m) - Eigen::Vector3i::Constant(2);
  const Eigen::Vector3i max_key = grid.KeyOf(bounds.max_m) + Eigen::Vector3i::Constant(2);
  grid.size = max_key - grid.min_key + Eigen::Vector3i::Ones();
  const std::size_t cells = static_cast<std::size_t>(grid.size.x()) * grid.size.y() * grid.size.z();
  constexpr std::size_t kMaxCells = std::size_t{1} << 30;
  if (cells > kMaxCells) throw InputError("ExposedVoxels: the scene is too large for a " + std::to_string(voxel_m) + " m grid");

  // 1 = touched by a triangle, 2 = empty and reached from the seed.
  std::vector<std::uint8_t> state(cells, 0);
  const double step = 0.4 * voxel_m;
  for (const auto& o : scene.objects()) {
    for (const auto& t : o.mesh.triangles) {
      const Eigen::Vector3d a = o.T_world_object * o.mesh.vertices[t[0]].cast<double>();
      const Eigen::Vector3d b = o.T_world_object * o.mesh.vertices[t[1]].cast<double>();
      const Eigen::Vector3d c = o.T_world_object * o.mesh.vertices[t[2]].cast<double>();
      SampleTriangle(a, b, c, step, [&](const Eigen::Vector3d& p) {
        const Eigen::Vector3i k = grid.KeyOf(p);
        if (grid.Inside(k)) state[grid.Index(k)] = 1;
      });
    }
  }

  // The seed: its own voxel when empty, else the nearest empty voxel within two.
  const Eigen::Vector3i seed_key = grid.KeyOf(seed_world);
  Eigen::Vector3i seed = seed_key;
  bool found = grid.Inside(seed) && state[grid.Index(seed)] == 0;
  for (int r = 1; r <= 2 && !found; ++r) {
    double best = 1e18;
    for (int dz = -r; dz <= r; ++dz)
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          const Eigen::Vector3i k = seed_key + Eigen::Vector3i(dx, dy, dz);
          if (!grid.Inside(k) || state[grid.Index(k)] != 0) continue;
          const double d = ((k.cast<double>() + Eigen::Vector3d::Constant(0.5)) * voxel_m - seed_world).squaredNorm();
          if (d < best) {
            best = d;
            seed = k;
            found = true;
          }
        }
  }
  if (!found) return exposed;

  // Camera air is above the floor and below the wall tops: without a ceiling, air flowing over the
  // walls and under the floor would reach the undersides of objects resting on the floor and the
  // outer faces of windows.
  int z_lo = grid.min_key.z(), z_hi = grid.min_key.z() + grid.size.z() - 1;
  const geometry::Aabb3 floors = scene.StructureBounds(world::Category::kFloor);
  if (!floors.Empty()) z_lo = std::max(z_lo, grid.KeyOf(floors.max_m).z());
  const geometry::Aabb3 walls = scene.StructureBounds(world::Category::kWall);
  if (!walls.Empty()) z_hi = std::min(z_hi, grid.KeyOf(walls.max_m).z() - 1);
  if (seed.z() < z_lo || seed.z() > z_hi) return exposed;

  std::deque<Eigen::Vector3i> queue{seed};
  state[grid.Index(seed)] = 2;
  while (!queue.empty()) {
    const Eigen::Vector3i k = queue.front();
    queue.pop_front();
    for (const auto& d : kFaceNeighbours) {
      const Eigen::Vector3i n = k + d;
      if (!grid.Inside(n) || n.z() < z_lo || n.z() > z_hi) continue;
      std::uint8_t& s = state[grid.Index(n)];
      if (s != 0) continue;
      s = 2;
      queue.push_back(n);
    }
  }

  // The band in world heights, and the voxel layers whose lower (upper) faces a camera in it can see.
  const double floor_top_m = floors.Empty() ? 0.0 : floors.max_m.z();
  const double min_camera_z_m = floor_top_m + band.min_height_m;
  const double max_camera_z_m = floor_top_m + band.max_height_m;
  auto face_visible = [&](const Eigen::Vector3i& k, const Eigen::Vector3i& d) {
    if (d.z() < 0) return (k.z() + 1) * voxel_m > min_camera_z_m;
    if (d.z() > 0) return k.z() * voxel_m < max_camera_z_m;
    return true;
  };
  for (std::size_t i = 0; i < voxel_centers_world.size(); ++i) {
    const Eigen::Vector3i k = grid.KeyOf(voxel_centers_world[i]);
    for (const auto& d : kFaceNeighbours) {
      const Eigen::Vector3i n = k + d;
      if (grid.Inside(n) && state[grid.Index(n)] == 2 && face_visible(k, d)) {
        exposed[i] = 1;
        break;
      }
    }
  }
  return exposed;
}

}  // namespace objscan::eval
