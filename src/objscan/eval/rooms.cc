#include "objscan/eval/rooms.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "objscan/common/config.h"
#include "objscan/geometry/mesh.h"

namespace objscan::eval {
namespace {

Eigen::Affine3d AsAffine(const geometry::Pose3& T) { return Eigen::Affine3d(T.matrix()); }

}  // namespace

RoomPartition RoomPartition::FromScene(const world::Scene& scene, const RoomPartitionOptions& options) {
  config::RequirePositive("rooms.cell_m", options.cell_m);
  config::RequireNonNegative("rooms.min_room_area_m2", options.min_room_area_m2);
  config::RequireNonNegative("rooms.margin_m", options.margin_m);
  config::RequireNonNegative("rooms.doorway_width_m", options.doorway_width_m);
  config::Require(options.blocking_max_z_m > options.blocking_min_z_m, "rooms.blocking_max_z_m",
                  "must be above blocking_min_z_m");
  RoomPartition p;
  p.cell_m_ = options.cell_m;
  const geometry::Aabb3 furniture = scene.FurnitureBounds();
  if (furniture.Empty()) return p;
  p.origin_m_ = furniture.min_m.head<2>() - Eigen::Vector2d::Constant(options.margin_m);
  const Eigen::Vector2d extent = furniture.max_m.head<2>() - furniture.min_m.head<2>() +
                                 Eigen::Vector2d::Constant(2.0 * options.margin_m);
  p.nx_ = std::max(1, static_cast<int>(std::ceil(extent.x() / options.cell_m)));
  p.ny_ = std::max(1, static_cast<int>(std::ceil(extent.y() / options.cell_m)));
  const std::size_t n_cells = static_cast<std::size_t>(p.nx_) * static_cast<std::size_t>(p.ny_);
  std::vector<char> floor(n_cells, 0), blocked(n_cells, 0);
  auto cell_of = [&](double x, double y, int* ix, int* iy) {
    *ix = static_cast<int>(std::floor((x - p.origin_m_.x()) / options.cell_m));
    *iy = static_cast<int>(std::floor((y - p.origin_m_.y()) / options.cell_m));
    return *ix >= 0 && *iy >= 0 && *ix < p.nx_ && *iy < p.ny_;
  };

  // Floor cells: cell centres inside an upward (or downward) facing floor triangle, seen from above.
  double floor_z = std::numeric_limits<double>::infinity();
  std::vector<geometry::TriangleMesh> floors, blockers;
  for (const world::SceneObject& o : scene.objects()) {
    if (o.category == world::Category::kFloor) {
      floors.push_back(geometry::Transformed(o.mesh, AsAffine(o.T_world_object)));
    } else if (o.category == world::Category::kWall || o.category == world::Category::kDoor) {
      blockers.push_back(geometry::Transformed(o.mesh, AsAffine(o.T_world_object)));
    }
  }
  for (const geometry::TriangleMesh& mesh : floors) {
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                            c = mesh.vertices[t[2]].cast<double>();
      const Eigen::Vector3d n = (b - a).cross(c - a);
      if (n.norm() <= 0.0 || std::abs(n.z()) < 0.5 * n.norm()) continue;
      floor_z = std::min(floor_z, std::min({a.z(), b.z(), c.z()}));
      const double area2 = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
      int x0, y0, x1, y1;
      cell_of(std::min({a.x(), b.x(), c.x()}), std::min({a.y(), b.y(), c.y()}), &x0, &y0);
      cell_of(std::max({a.x(), b.x(), c.x()}), std::max({a.y(), b.y(), c.y()}), &x1, &y1);
      x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, p.nx_ - 1), y1 = std::min(y1, p.ny_ - 1);
      for (int iy = y0; iy <= y1; ++iy) {
        for (int ix = x0; ix <= x1; ++ix) {
          const double px = p.origin_m_.x() + (ix + 0.5) * options.cell_m;
          const double py = p.origin_m_.y() + (iy + 0.5) * options.cell_m;
          // Barycentric signs relative to the triangle's orientation.
          const double w0 = (b.x() - px) * (c.y() - py) - (b.y() - py) * (c.x() - px);
          const double w1 = (c.x() - px) * (a.y() - py) - (c.y() - py) * (a.x() - px);
          const double w2 = (a.x() - px) * (b.y() - py) - (a.y() - py) * (b.x() - px);
          const bool inside = area2 > 0 ? (w0 >= 0 && w1 >= 0 && w2 >= 0) : (w0 <= 0 && w1 <= 0 && w2 <= 0);
          if (inside) floor[static_cast<std::size_t>(iy) * p.nx_ + ix] = 1;
        }
      }
    }
  }
  if (!std::isfinite(floor_z)) return p;

  // Blocked cells: wall and door surface between the blocking heights, sampled at half a cell.
  const double z_lo = floor_z + options.blocking_min_z_m, z_hi = floor_z + options.blocking_max_z_m;
  for (const geometry::TriangleMesh& mesh : blockers) {
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                            c = mesh.vertices[t[2]].cast<double>();
      if (std::max({a.z(), b.z(), c.z()}) < z_lo || std::min({a.z(), b.z(), c.z()}) > z_hi) continue;
      const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
      const int n = std::max(1, static_cast<int>(std::ceil(longest / (0.5 * options.cell_m))));
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; i + j <= n; ++j) {
          const Eigen::Vector3d q = a + (b - a) * (static_cast<double>(i) / n) + (c - a) * (static_cast<double>(j) / n);
          if (q.z() < z_lo || q.z() > z_hi) continue;
          int ix, iy;
          if (cell_of(q.x(), q.y(), &ix, &iy)) blocked[static_cast<std::size_t>(iy) * p.nx_ + ix] = 1;
        }
      }
    }
  }

  // Room cores: free cells with no wall, door or floor edge within half a doorway; connected
  // regions of them (4-neighbours).
  std::vector<char> free(n_cells, 0);
  for (std::size_t k = 0; k < n_cells; ++k) free[k] = floor[k] && !blocked[k];
  const double clearance_cells = 0.5 * options.doorway_width_m / options.cell_m;
  const int reach = static_cast<int>(std::ceil(clearance_cells));
  std::vector<char> core(n_cells, 0);
  for (int iy = 0; iy < p.ny_; ++iy) {
    for (int ix = 0; ix < p.nx_; ++ix) {
      if (!free[static_cast<std::size_t>(iy) * p.nx_ + ix]) continue;
      bool clear = true;
      for (int dy = -reach; dy <= reach && clear; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
          if (dx * dx + dy * dy > clearance_cells * clearance_cells) continue;
          const int qx = ix + dx, qy = iy + dy;
          if (qx < 0 || qy < 0 || qx >= p.nx_ || qy >= p.ny_ || !free[static_cast<std::size_t>(qy) * p.nx_ + qx]) {
            clear = false;
            break;
          }
        }
      }
      core[static_cast<std::size_t>(iy) * p.nx_ + ix] = clear;
    }
  }
  auto neighbours = [&](int k, auto&& visit) {
    const int kx = k % p.nx_, ky = k / p.nx_;
    if (kx > 0) visit(k - 1);
    if (kx + 1 < p.nx_) visit(k + 1);
    if (ky > 0) visit(k - p.nx_);
    if (ky + 1 < p.ny_) visit(k + p.nx_);
  };
  std::vector<int> region(n_cells, -1);
  int n_regions = 0;
  for (std::size_t s = 0; s < n_cells; ++s) {
    if (!core[s] || region[s] >= 0) continue;
    std::deque<int> queue{static_cast<int>(s)};
    region[s] = n_regions;
    while (!queue.empty()) {
      const int k = queue.front();
      queue.pop_front();
      neighbours(k, [&](int m) {
        if (core[static_cast<std::size_t>(m)] && region[static_cast<std::size_t>(m)] < 0) {
          region[static_cast<std::size_t>(m)] = n_regions;
          queue.push_back(m);
        }
      });
    }
    ++n_regions;
  }
  // The free cells near a core join the core they reach first over free floor (breadth first from
  // all cores at once, in cell order: deterministic), up to the eroded half doorway plus a cell, so
  // that floor beyond a gap (outside the house, past a window) joins no room.
  {
    std::deque<int> queue;
    std::vector<int> depth(n_cells, 0);
    for (std::size_t k = 0; k < n_cells; ++k) {
      if (region[k] >= 0) queue.push_back(static_cast<int>(k));
    }
    while (!queue.empty()) {
      const int k = queue.front();
      queue.pop_front();
      if (depth[static_cast<std::size_t>(k)] > reach) continue;
      neighbours(k, [&](int m) {
        if (free[static_cast<std::size_t>(m)] && region[static_cast<std::size_t>(m)] < 0) {
          region[static_cast<std::size_t>(m)] = region[static_cast<std::size_t>(k)];
          depth[static_cast<std::size_t>(m)] = depth[static_cast<std::size_t>(k)] + 1;
          queue.push_back(m);
        }
      });
    }
  }
  std::vector<std::vector<int>> regions(static_cast<std::size_t>(n_regions));
  for (std::size_t k = 0; k < n_cells; ++k) {
    if (region[k] >= 0) regions[static_cast<std::size_t>(region[k])].push_back(static_cast<int>(k));
  }
  const double cell_area = options.cell_m * options.cell_m;
  std::vector<int> order;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    if (regions[r].size() * cell_area >= options.min_room_area_m2) order.push_back(static_cast<int>(r));
  }
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return regions[x].size() > regions[y].size(); });
  p.cell_room_.assign(n_cells, -1);
  for (std::size_t k = 0; k < order.size(); ++k) {
    Room room;
    room.id = static_cast<int>(k);
    room.area_m2 = regions[order[k]].size() * cell_area;
    for (int c : regions[order[k]]) {
      p.cell_room_[static_cast<std::size_t>(c)] = room.id;
      room.center_m += p.origin_m_ + Eigen::Vector2d((c % p.nx_ + 0.5) * options.cell_m, (c / p.nx_ + 0.5) * options.cell_m);
    }
    room.center_m /= static_cast<double>(regions[order[k]].size());
    p.rooms_.push_back(room);
  }
  return p;
}

int RoomPartition::CellRoom(int ix, int iy) const {
  if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_ || cell_room_.empty()) return -1;
  return cell_room_[static_cast<std::size_t>(iy) * nx_ + ix];
}

std::vector<int> RoomPartition::RoomsWithin(double x_m, double y_m, double search_m) const {
  const int ix = static_cast<int>(std::floor((x_m - origin_m_.x()) / cell_m_));
  const int iy = static_cast<int>(std::floor((y_m - origin_m_.y()) / cell_m_));
  const int reach = static_cast<int>(std::ceil(search_m / cell_m_));
  std::vector<int> rooms;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      if (static_cast<long>(dx) * dx + static_cast<long>(dy) * dy > static_cast<long>(reach) * reach) continue;
      const int r = CellRoom(ix + dx, iy + dy);
      if (r >= 0 && std::find(rooms.begin(), rooms.end(), r) == rooms.end()) rooms.push_back(r);
    }
  }
  std::sort(rooms.begin(), rooms.end());
  return rooms;
}

int RoomPartition::RoomAt(double x_m, double y_m, double search_m) const {
  const int ix = static_cast<int>(std::floor((x_m - origin_m_.x()) / cell_m_));
  const int iy = static_cast<int>(std::floor((y_m - origin_m_.y()) / cell_m_));
  if (const int r = CellRoom(ix, iy); r >= 0) return r;
  const int reach = static_cast<int>(std::ceil(search_m / cell_m_));
  int best = -1;
  long best_d2 = std::numeric_limits<long>::max();
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const long d2 = static_cast<long>(dx) * dx + static_cast<long>(dy) * dy;
      if (d2 > static_cast<long>(reach) * reach || d2 >= best_d2) continue;
      const int r = CellRoom(ix + dx, iy + dy);
      if (r < 0) continue;
      best = r;
      best_d2 = d2;
    }
  }
  return best;
}

}  // namespace objscan::eval
