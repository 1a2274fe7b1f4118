#include "objscan/eval/exposure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <string>

#include "objscan/common/error.h"
#include "objscan/common/limits.h"

namespace objscan::eval {
namespace {

const std::array<Eigen::Vector3i, 6> kFaceNeighbours = {Eigen::Vector3i(1, 0, 0),  Eigen::Vector3i(-1, 0, 0),
                                                        Eigen::Vector3i(0, 1, 0),  Eigen::Vector3i(0, -1, 0),
                                                        Eigen::Vector3i(0, 0, 1),  Eigen::Vector3i(0, 0, -1)};

}  // namespace

Eigen::Vector3i RoomAir::KeyOf(const Eigen::Vector3d& p) const {
  return (p / voxel_m_).array().floor().cast<int>().matrix();
}

bool RoomAir::Inside(const Eigen::Vector3i& k) const {
  const Eigen::Vector3i r = k - min_key_;
  return (r.array() >= 0).all() && (r.array() < size_.array()).all();
}

std::size_t RoomAir::Index(const Eigen::Vector3i& k) const {
  const Eigen::Vector3i r = k - min_key_;
  return (static_cast<std::size_t>(r.z()) * size_.y() + r.y()) * size_.x() + r.x();
}

bool RoomAir::Contains(const Eigen::Vector3d& p_world) const {
  if (state_.empty() || !p_world.allFinite()) return false;
  const Eigen::Vector3i k = KeyOf(p_world);
  return Inside(k) && state_[Index(k)] == 2;
}

RoomAir::RoomAir(const world::Scene& scene, double voxel_m, const Eigen::Vector3d& seed_world) : voxel_m_(voxel_m) {
  if (!(voxel_m > 0.0)) throw InputError("ExposedVoxels: voxel_m must be positive");
  const geometry::Aabb3 floors = scene.StructureBounds(world::Category::kFloor);
  floor_top_m_ = floors.Empty() ? 0.0 : floors.max_m.z();
  const geometry::Aabb3 bounds = scene.Bounds();
  if (bounds.Empty()) return;
  // Two voxels of margin so the air around the scene's outside is one connected region.
  min_key_ = KeyOf(bounds.min_m) - Eigen::Vector3i::Constant(2);
  const Eigen::Vector3i max_key = KeyOf(bounds.max_m) + Eigen::Vector3i::Constant(2);
  size_ = max_key - min_key_ + Eigen::Vector3i::Ones();
  const std::size_t cells = static_cast<std::size_t>(size_.x()) * size_.y() * size_.z();
  if (cells > limits::kMaxEvaluationGridCells) throw InputError("ExposedVoxels: the scene is too large for a " + std::to_string(voxel_m) + " m grid");

  std::vector<std::uint8_t> state(cells, 0);
  const double step = 0.4 * voxel_m;
  for (const auto& o : scene.objects()) {
    for (const auto& t : o.mesh.triangles) {
      const Eigen::Vector3d a = o.T_world_object * o.mesh.vertices[t[0]].cast<double>();
      const Eigen::Vector3d b = o.T_world_object * o.mesh.vertices[t[1]].cast<double>();
      const Eigen::Vector3d c = o.T_world_object * o.mesh.vertices[t[2]].cast<double>();
      SampleTriangle(a, b, c, step, [&](const Eigen::Vector3d& p) {
        const Eigen::Vector3i k = KeyOf(p);
        if (Inside(k)) state[Index(k)] = 1;
      });
    }
  }

  // The seed: its own voxel when empty, else the nearest empty voxel within two.
  const Eigen::Vector3i seed_key = KeyOf(seed_world);
  Eigen::Vector3i seed = seed_key;
  bool found = Inside(seed) && state[Index(seed)] == 0;
  for (int r = 1; r <= 2 && !found; ++r) {
    double best = 1e18;
    for (int dz = -r; dz <= r; ++dz)
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          const Eigen::Vector3i k = seed_key + Eigen::Vector3i(dx, dy, dz);
          if (!Inside(k) || state[Index(k)] != 0) continue;
          const double d = ((k.cast<double>() + Eigen::Vector3d::Constant(0.5)) * voxel_m - seed_world).squaredNorm();
          if (d < best) {
            best = d;
            seed = k;
            found = true;
          }
        }
  }
  if (!found) return;

  // Camera air is above the floor and below the wall tops: without a ceiling, air flowing over the
  // walls and under the floor would reach the undersides of objects resting on the floor and the
  // outer faces of windows.
  int z_lo = min_key_.z(), z_hi = min_key_.z() + size_.z() - 1;
  if (!floors.Empty()) z_lo = std::max(z_lo, KeyOf(floors.max_m).z());
  const geometry::Aabb3 walls = scene.StructureBounds(world::Category::kWall);
  if (!walls.Empty()) z_hi = std::min(z_hi, KeyOf(walls.max_m).z() - 1);
  if (seed.z() < z_lo || seed.z() > z_hi) return;
  seed_key_ = seed;
  z_lo_ = z_lo;

  std::deque<Eigen::Vector3i> queue{seed};
  state[Index(seed)] = 2;
  while (!queue.empty()) {
    const Eigen::Vector3i k = queue.front();
    queue.pop_front();
    for (const auto& d : kFaceNeighbours) {
      const Eigen::Vector3i n = k + d;
      if (!Inside(n) || n.z() < z_lo || n.z() > z_hi) continue;
      std::uint8_t& s = state[Index(n)];
      if (s != 0) continue;
      s = 2;
      queue.push_back(n);
    }
  }
  state_ = std::move(state);
}

void RoomAir::RestrictToRobotReach(double base_radius_m, double base_height_m, double max_reach_m) {
  if (!(base_radius_m >= 0.0) || !(base_height_m >= 0.0) || !(max_reach_m >= 0.0)) {
    throw InputError("RoomAir: the robot's radius, height and reach must be non-negative");
  }
  const int nx = size_.x(), ny = size_.y();
  camera_xy_.clear();
  if (state_.empty()) return;
  camera_xy_.assign(static_cast<std::size_t>(nx) * ny, 0);
  // Columns that are air from the layer above the floor up to the robot's height.
  const int z_top = std::min(min_key_.z() + size_.z() - 1,
                             static_cast<int>(std::floor((floor_top_m_ + base_height_m) / voxel_m_)));
  std::vector<std::uint8_t> free(camera_xy_.size(), 0);
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx; ++x) {
      bool air = true;
      for (int z = std::max(z_lo_ + 1, min_key_.z()); z <= z_top && air; ++z) {
        air = state_[Index(Eigen::Vector3i(min_key_.x() + x, min_key_.y() + y, z))] == 2;
      }
      free[static_cast<std::size_t>(y) * nx + x] = air ? 1 : 0;
    }
  }
  // Disk offsets of a radius in cells (centre to centre).
  auto disk = [&](double radius_m) {
    std::vector<Eigen::Vector2i> offsets;
    const int r = static_cast<int>(std::ceil(radius_m / voxel_m_));
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        if ((dx * dx + dy * dy) * voxel_m_ * voxel_m_ <= radius_m * radius_m + 1e-12) offsets.emplace_back(dx, dy);
      }
    return offsets;
  };
  auto in = [&](int x, int y) { return x >= 0 && y >= 0 && x < nx && y < ny; };
  const std::vector<Eigen::Vector2i> base_disk = disk(base_radius_m);
  std::vector<std::uint8_t> base(camera_xy_.size(), 0);
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx; ++x) {
      bool fits = true;
      for (const auto& o : base_disk) {
        if (!in(x + o.x(), y + o.y()) || !free[static_cast<std::size_t>(y + o.y()) * nx + x + o.x()]) {
          fits = false;
          break;
        }
      }
      base[static_cast<std::size_t>(y) * nx + x] = fits ? 1 : 0;
    }
  }
  // Base positions joined to the seed's column, or to the nearest base cell within a metre of it (the
  // robot stands at the seed; a lamp hanging over it must not leave it nowhere). None: no limit.
  const Eigen::Vector2i seed_xy = (seed_key_ - min_key_).head<2>();
  Eigen::Vector2i start(-1, -1);
  double best = 1e18;
  for (const auto& o : disk(std::max(1.0, base_radius_m + voxel_m_))) {
    const Eigen::Vector2i c = seed_xy + o;
    if (!in(c.x(), c.y()) || !base[static_cast<std::size_t>(c.y()) * nx + c.x()]) continue;
    if (o.squaredNorm() < best) {
      best = o.squaredNorm();
      start = c;
    }
  }
  if (start.x() < 0) {
    camera_xy_.clear();
    return;
  }
  std::vector<std::uint8_t> reached(base.size(), 0);
  std::deque<Eigen::Vector2i> queue{start};
  reached[static_cast<std::size_t>(start.y()) * nx + start.x()] = 1;
  const std::vector<Eigen::Vector2i> reach_disk = disk(max_reach_m);
  while (!queue.empty()) {
    const Eigen::Vector2i c = queue.front();
    queue.pop_front();
    for (const auto& o : reach_disk) {
      if (in(c.x() + o.x(), c.y() + o.y())) camera_xy_[static_cast<std::size_t>(c.y() + o.y()) * nx + c.x() + o.x()] = 1;
    }
    for (const Eigen::Vector2i& d : {Eigen::Vector2i(1, 0), Eigen::Vector2i(-1, 0), Eigen::Vector2i(0, 1), Eigen::Vector2i(0, -1)}) {
      const Eigen::Vector2i n = c + d;
      if (!in(n.x(), n.y())) continue;
      const std::size_t i = static_cast<std::size_t>(n.y()) * nx + n.x();
      if (!base[i] || reached[i]) continue;
      reached[i] = 1;
      queue.push_back(n);
    }
  }
}

bool RoomAir::CameraCanBeAt(const Eigen::Vector3d& p_world) const {
  if (!Contains(p_world)) return false;
  if (camera_xy_.empty()) return true;
  const Eigen::Vector3i r = KeyOf(p_world) - min_key_;
  return camera_xy_[static_cast<std::size_t>(r.y()) * size_.x() + r.x()] != 0;
}

std::vector<char> RoomAir::Exposed(const std::vector<Eigen::Vector3d>& voxel_centers_world,
                                   const CameraHeightBand& band) const {
  if (std::isnan(band.min_height_m) || std::isnan(band.max_height_m) || band.min_height_m > band.max_height_m) {
    throw InputError("ExposedVoxels: the camera height band must be an interval");
  }
  std::vector<char> exposed(voxel_centers_world.size(), 0);
  if (state_.empty()) return exposed;
  // The band in world heights, and the voxel layers whose lower (upper) faces a camera in it can see.
  const double min_camera_z_m = floor_top_m_ + band.min_height_m;
  const double max_camera_z_m = floor_top_m_ + band.max_height_m;
  auto face_visible = [&](const Eigen::Vector3i& k, const Eigen::Vector3i& d) {
    if (d.z() < 0) return (k.z() + 1) * voxel_m_ > min_camera_z_m;
    if (d.z() > 0) return k.z() * voxel_m_ < max_camera_z_m;
    return true;
  };
  for (std::size_t i = 0; i < voxel_centers_world.size(); ++i) {
    const Eigen::Vector3i k = KeyOf(voxel_centers_world[i]);
    for (const auto& d : kFaceNeighbours) {
      const Eigen::Vector3i n = k + d;
      if (Inside(n) && state_[Index(n)] == 2 && face_visible(k, d)) {
        exposed[i] = 1;
        break;
      }
    }
  }
  return exposed;
}

std::vector<char> ExposedVoxels(const world::Scene& scene, const std::vector<Eigen::Vector3d>& voxel_centers_world,
                                double voxel_m, const Eigen::Vector3d& seed_world, const CameraHeightBand& band) {
  return RoomAir(scene, voxel_m, seed_world).Exposed(voxel_centers_world, band);
}

}  // namespace objscan::eval
