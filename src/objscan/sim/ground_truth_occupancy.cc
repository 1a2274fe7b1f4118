#include "objscan/sim/ground_truth_occupancy.h"

#include <algorithm>
#include <cmath>

#include "objscan/common/error.h"

namespace objscan::sim {

using navigation::CellState;
using navigation::OccupancyGrid2D;

namespace {

// Clips a convex polygon to the half-space sign * (z - z0) >= 0 (Sutherland-Hodgman, one plane).
std::vector<Eigen::Vector3d> ClipZ(const std::vector<Eigen::Vector3d>& polygon, double z0, double sign) {
  std::vector<Eigen::Vector3d> out;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = polygon[i];
    const Eigen::Vector3d& b = polygon[(i + 1) % n];
    const double da = sign * (a.z() - z0), db = sign * (b.z() - z0);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

// Calls mark(ix, iy) for every grid cell the convex polygon (XY) touches, boundaries included
// (separating axis test against each candidate cell).
template <class Mark>
void RasterizeConservative(const std::vector<Eigen::Vector2d>& polygon, const OccupancyGrid2D& grid, Mark mark) {
  Eigen::Vector2d lo = polygon[0], hi = polygon[0];
  for (const auto& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2i c0 = grid.CellOf(lo), c1 = grid.CellOf(hi);
  // A boundary exactly on a cell edge touches the cell below too.
  const int ix0 = std::max(0, c0.x() - 1), iy0 = std::max(0, c0.y() - 1);
  const int ix1 = std::min(grid.width - 1, c1.x()), iy1 = std::min(grid.height - 1, c1.y());
  // Edge normals of the polygon (separating axes besides X and Y).
  std::vector<Eigen::Vector2d> axes;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d e = polygon[(i + 1) % polygon.size()] - polygon[i];
    if (e.squaredNorm() > 1e-18) axes.emplace_back(-e.y(), e.x());
  }
  const double s = grid.cell_size_m;
  for (int iy = iy0; iy <= iy1; ++iy) {
    for (int ix = ix0; ix <= ix1; ++ix) {
      const Eigen::Vector2d cmin = grid.origin_m + s * Eigen::Vector2d(ix, iy);
      const Eigen::Vector2d cmax = cmin + Eigen::Vector2d(s, s);
      if (hi.x() < cmin.x() || lo.x() > cmax.x() || hi.y() < cmin.y() || lo.y() > cmax.y()) continue;
      bool separated = false;
      for (const auto& axis : axes) {
        double pmin = INFINITY, pmax = -INFINITY;
        for (const auto& p : polygon) {
          const double d = axis.dot(p);
          pmin = std::min(pmin, d);
          pmax = std::max(pmax, d);
        }
        // Projection of the square: centre +- half extent along the axis.
        const double centre = axis.dot(0.5 * (cmin + cmax));
        const double half = 0.5 * s * (std::abs(axis.x()) + std::abs(axis.y()));
        if (pmax < centre - half || pmin > centre + half) {
          separated = true;
          break;
        }
      }
      if (!separated) mark(ix, iy);
    }
  }
}

// Calls mark(ix, iy) for every cell whose centre lies inside the triangle's XY projection.
template <class Mark>
void RasterizeCentres(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                      const OccupancyGrid2D& grid, Mark mark) {
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return (p - o).x() * (q - o).y() - (p - o).y() * (q - o).x();
  };
  const double area = cross(a, b, c);
  if (std::abs(area) < 1e-12) return;
  const Eigen::Vector2d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
  const Eigen::Vector2i c0 = grid.CellOf(lo), c1 = grid.CellOf(hi);
  for (int iy = std::max(0, c0.y()); iy <= std::min(grid.height - 1, c1.y()); ++iy) {
    for (int ix = std::max(0, c0.x()); ix <= std::min(grid.width - 1, c1.x()); ++ix) {
      const Eigen::Vector2d p = grid.CellCenter(ix, iy);
      const double w0 = cross(b, c, p) / area, w1 = cross(c, a, p) / area, w2 = cross(a, b, p) / area;
      if (w0 >= 0 && w1 >= 0 && w2 >= 0) mark(ix, iy);
    }
  }
}

}  // namespace

GroundTruthOccupancy::GroundTruthOccupancy(const world::Scene& scene, double margin_m) {
  if (!(margin_m >= 0.0)) throw InputError("ground-truth occupancy: margin_m must be >= 0");
  geometry::Aabb3 obstacle_bounds, floor_bounds;
  for (const auto& object : scene.objects()) {
    const bool is_floor = object.category == world::Category::kFloor;
    auto& out = is_floor ? floor_triangles_ : obstacle_triangles_;
    for (const auto& t : object.mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= object.mesh.vertices.size()) {
          throw InputError("scene object '" + object.name + "': triangle vertex index out of range");
        }
        const Eigen::Vector3d v = object.T_world_object * object.mesh.vertices[t[k]].cast<double>();
        out.push_back(v);
        (is_floor ? floor_bounds : obstacle_bounds).Extend(v);
      }
    }
  }
  const geometry::Aabb3& bounds = obstacle_bounds.Empty() ? floor_bounds : obstacle_bounds;
  if (bounds.Empty()) throw InputError("scene '" + scene.name() + "': no triangles for an occupancy grid");
  min_xy_ = bounds.min_m.head<2>() - Eigen::Vector2d::Constant(margin_m);
  max_xy_ = bounds.max_m.head<2>() + Eigen::Vector2d::Constant(margin_m);
}

OccupancyGrid2D GroundTruthOccupancy::Grid(double min_z_m, double max_z_m, double cell_size_m) const {
  if (!(max_z_m > min_z_m)) throw InputError("ground-truth occupancy: need max_z_m > min_z_m");
  const bool has_floor = !floor_triangles_.empty();
  OccupancyGrid2D grid =
      OccupancyGrid2D::Covering(min_xy_, max_xy_, cell_size_m, has_floor ? CellState::kUnknown : CellState::kFree);
  for (std::size_t t = 0; t + 2 < floor_triangles_.size(); t += 3) {
    RasterizeCentres(floor_triangles_[t].head<2>(), floor_triangles_[t + 1].head<2>(),
                     floor_triangles_[t + 2].head<2>(), grid,
                     [&](int ix, int iy) { grid.cells[grid.Index(ix, iy)] = CellState::kFree; });
  }
  std::vector<Eigen::Vector3d> polygon;
  std::vector<Eigen::Vector2d> polygon_xy;
  for (std::size_t t = 0; t + 2 < obstacle_triangles_.size(); t += 3) {
    const Eigen::Vector3d* v = &obstacle_triangles_[t];
    const double z_lo = std::min({v[0].z(), v[1].z(), v[2].z()});
    const double z_hi = std::max({v[0].z(), v[1].z(), v[2].z()});
    // The band is open: a triangle only touching its bottom (a rug on the floor) is drivable.
    if (z_hi <= min_z_m || z_lo >= max_z_m) continue;
    polygon.assign(v, v + 3);
    if (z_lo < min_z_m) polygon = ClipZ(polygon, min_z_m, +1.0);
    if (z_hi > max_z_m && !polygon.empty()) polygon = ClipZ(polygon, max_z_m, -1.0);
    if (polygon.empty()) continue;
    polygon_xy.clear();
    for (const auto& p : polygon) polygon_xy.push_back(p.head<2>());
    RasterizeConservative(polygon_xy, grid,
                          [&](int ix, int iy) { grid.cells[grid.Index(ix, iy)] = CellState::kOccupied; });
  }
  return grid;
}

}  // namespace objscan::sim
