#include "objscan/mapping/occupancy_map.h"

#include <octomap/OcTree.h>
#include <octomap/octomap.h>

#include <algorithm>
#include <cmath>

#include "objscan/common/limits.h"

namespace objscan::mapping {

using navigation::CellState;
using navigation::OccupancyGrid2D;

namespace {

// Cells [*first, *last] along one axis of a grid (origin `lo`, cell size `res`, `count` cells) that
// an octree leaf spanning [c - half, c + half] overlaps (by more than a rounding error); empty when
// *first > *last.
void LeafCellRange(double c, double half, double lo, double res, int count, int* first, int* last) {
  *first = std::max(0, static_cast<int>(std::floor((c - half - lo) / res + 1e-6)));
  *last = std::min(count - 1, static_cast<int>(std::ceil((c + half - lo) / res - 1e-6)) - 1);
}

}  // namespace

void OccupancyMapOptions::Validate() const {
  config::RequireInRange("resolution_m", resolution_m, 0.005, 1.0);
  config::RequireInRange("pixel_stride", pixel_stride, 1, 64);
  config::RequirePositive("max_range_m", max_range_m);
  config::RequireInRange("prob_hit", prob_hit, 0.5, 1.0);
  config::RequireInRange("prob_miss", prob_miss, 0.0, 0.5);
  config::RequireInRange("clamping_min", clamping_min, 0.0, 0.5);
  config::RequireInRange("clamping_max", clamping_max, 0.5, 1.0);
  config::RequireInRange("occupied_threshold", occupied_threshold, 0.0, 1.0);
  config::RequireNonNegative("view_clearance_m", view_clearance_m);
  config::RequireInRange("floor_clearance_m", floor_clearance_m, 0.0, 0.5);
}

struct OccupancyMap::Impl {
  explicit Impl(double resolution) : tree(resolution), resolution_m(resolution) {}
  octomap::OcTree tree;
  double resolution_m;
  // Bounds of every voxel a ray has touched, kept as rays come in (OcTree::getMetricMin/Max walk
  // every leaf after each insertion): a ray's voxels lie between its start and end voxels, grown by
  // one voxel for the traversal's rounding at voxel faces.
  geometry::Aabb3 known_box;
  void ExtendKnown(const Eigen::Vector3d& p) {
    const Eigen::Vector3d lo = (p / resolution_m).array().floor() * resolution_m;
    known_box.Extend(lo - Eigen::Vector3d::Constant(resolution_m));
    known_box.Extend(lo + Eigen::Vector3d::Constant(2.0 * resolution_m));
  }
};

OccupancyMap::OccupancyMap(const OccupancyMapOptions& options) : options_(options) {
  options_.Validate();
  impl_ = std::make_unique<Impl>(options_.resolution_m);
  octomap::OcTree& tree = impl_->tree;
  tree.setProbHit(options_.prob_hit);
  tree.setProbMiss(options_.prob_miss);
  tree.setClampingThresMin(options_.clamping_min);
  tree.setClampingThresMax(options_.clamping_max);
  tree.setOccupancyThres(options_.occupied_threshold);
}

OccupancyMap::~OccupancyMap() = default;

void OccupancyMap::Integrate(const platform::DepthFrame& frame) {
  const int stride = options_.pixel_stride;
  const Eigen::Matrix3f R = frame.T_world_camera.rotation().cast<float>();
  const Eigen::Vector3f t = frame.T_world_camera.translation().cast<float>();
  const platform::CameraIntrinsics& in = frame.intrinsics;
  std::vector<Eigen::Vector3f> end_points;
  end_points.reserve(static_cast<std::size_t>(frame.width() / stride + 1) * (frame.height() / stride + 1));
  // Offset the sample grid by half a stride so samples sit in the middle of their blocks.
  for (int v = stride / 2; v < frame.height(); v += stride) {
    for (int u = stride / 2; u < frame.width(); u += stride) {
      const float z = frame.Depth(u, v);
      if (z <= 0.f) continue;
      const Eigen::Vector3f p_camera(static_cast<float>((u - in.cx_px) / in.fx_px) * z,
                                     static_cast<float>((v - in.cy_px) / in.fy_px) * z, z);
      end_points.push_back(R * p_camera + t);
    }
  }
  InsertRays(frame.T_world_camera.translation(), end_points);
}

void OccupancyMap::InsertRays(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3f>& end_points) {
  octomap::OcTree& tree = impl_->tree;
  const octomap::point3d o(origin.x(), origin.y(), origin.z());
  const double floor_z = options_.floor_clearance_m;
  octomap::Pointcloud cloud;
  cloud.reserve(end_points.size());
  // Floor rays first (free space only), then the hits, so a hit wins over a floor ray in one frame.
  octomap::KeySet floor_free;
  octomap::KeyRay ray;
  impl_->ExtendKnown(origin);
  for (const Eigen::Vector3f& p : end_points) {
    if (!(floor_z > 0.0 && p.z() < floor_z)) {
      // Rays end at the range limit (insertPointCloud clips them there).
      Eigen::Vector3d reach = p.cast<double>();
      if ((reach - origin).norm() > options_.max_range_m) {
        reach = origin + (reach - origin).normalized() * options_.max_range_m;
      }
      impl_->ExtendKnown(reach);
    }
    if (floor_z > 0.0 && p.z() < floor_z) {
      if (origin.z() <= floor_z) continue;
      // Clear the ray up to where it comes down to floor_z (and never beyond the range limit).
      Eigen::Vector3d end = p.cast<double>();
      const double t = (origin.z() - floor_z) / (origin.z() - end.z());
      end = origin + t * (end - origin);
      if ((end - origin).norm() > options_.max_range_m) {
        end = origin + (end - origin).normalized() * options_.max_range_m;
      }
      impl_->ExtendKnown(end);
      if (tree.computeRayKeys(o, octomap::point3d(end.x(), end.y(), end.z()), ray)) {
        floor_free.insert(ray.begin(), ray.end());
      }
      continue;
    }
    cloud.push_back(p.x(), p.y(), p.z());
  }
  for (const octomap::OcTreeKey& key : floor_free) tree.updateNode(key, false, /*lazy_eval=*/false);
  // discretize = true: rays to end points in the same voxel are cast once (much faster, same map).
  if (cloud.size() > 0) {
    tree.insertPointCloud(cloud, o, options_.max_range_m, /*lazy_eval=*/false, /*discretize=*/true);
  }
}

Occupancy OccupancyMap::Query(const Eigen::Vector3d& p) const {
  const octomap::OcTreeNode* node = impl_->tree.search(p.x(), p.y(), p.z());
  if (node == nullptr) return Occupancy::kUnknown;
  return impl_->tree.isNodeOccupied(node) ? Occupancy::kOccupied : Occupancy::kFree;
}

bool OccupancyMap::IsViewValid(const Eigen::Vector3d& c) const {
  if (Query(c) != Occupancy::kFree) return false;
  const double r = options_.view_clearance_m;
  if (r <= 0.0) return true;
  static const double kDirs[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& d : kDirs) {
    if (Query(c + r * Eigen::Vector3d(d[0], d[1], d[2])) != Occupancy::kFree) return false;
  }
  return true;
}

void OccupancyMap::ForEachOccupied(
    const std::function<void(const Eigen::Vector3d& center, double size_m)>& fn) const {
  const octomap::OcTree& tree = impl_->tree;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const octomap::point3d c = it.getCoordinate();
    fn(Eigen::Vector3d(c.x(), c.y(), c.z()), it.getSize());
  }
}

std::size_t OccupancyMap::NumOccupied() const {
  std::size_t n = 0;
  const double res = options_.resolution_m;
  ForEachOccupied([&n, res](const Eigen::Vector3d&, double size_m) {
    // Counted in finest voxels: a pruned leaf stands for (size / res)^3 of them.
    const double k = size_m / res;
    n += static_cast<std::size_t>(std::lround(k * k * k));
  });
  return n;
}

geometry::Aabb3 OccupancyMap::KnownBounds() const { return impl_->known_box; }

OccupancyGrid2D OccupancyMap::Grid(double min_z_m, double max_z_m, double cell_size_m) const {
  return GridOver(KnownBounds(), min_z_m, max_z_m, cell_size_m);
}

OccupancyGrid2D OccupancyMap::GridOver(const geometry::Aabb3& box, double min_z_m, double max_z_m,
                                            double cell_size_m) const {
  if (!(cell_size_m > 0.0)) throw InputError("OccupancyMap::Grid: cell_size_m must be positive");
  if (box.Empty()) {
    return OccupancyGrid2D::Covering(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), cell_size_m,
                                          CellState::kUnknown);
  }
  // Cells aligned to multiples of the cell size, so they line up with the voxels.
  const Eigen::Vector2d min_xy = (box.min_m.head<2>() / cell_size_m).array().floor() * cell_size_m;
  OccupancyGrid2D grid =
      OccupancyGrid2D::Covering(min_xy, box.max_m.head<2>(), cell_size_m, CellState::kUnknown);
  const double res = cell_size_m;
  const octomap::OcTree& tree = impl_->tree;
  const octomap::point3d bbx_min(grid.origin_m.x(), grid.origin_m.y(), min_z_m);
  const octomap::point3d bbx_max(grid.origin_m.x() + grid.width * res, grid.origin_m.y() + grid.height * res, max_z_m);
  std::vector<std::uint8_t> known(grid.cells.size(), 0), occupied(grid.cells.size(), 0);
  const double voxel = options_.resolution_m;
  for (auto it = tree.begin_leafs_bbx(bbx_min, bbx_max), end = tree.end_leafs_bbx(); it != end; ++it) {
    const octomap::point3d c = it.getCoordinate();
    const double half = 0.5 * it.getSize();
    // Leaves whose centre lies outside the band only graze it.
    if (c.z() < min_z_m - 0.5 * voxel || c.z() > max_z_m + 0.5 * voxel) continue;
    const bool occ = tree.isNodeOccupied(*it);
    int ix0, ix1, iy0, iy1;
    LeafCellRange(c.x(), half, grid.origin_m.x(), res, grid.width, &ix0, &ix1);
    LeafCellRange(c.y(), half, grid.origin_m.y(), res, grid.height, &iy0, &iy1);
    for (int iy = iy0; iy <= iy1; ++iy) {
      for (int ix = ix0; ix <= ix1; ++ix) {
        const std::size_t k = grid.Index(ix, iy);
        known[k] = 1;
        if (occ) occupied[k] = 1;
      }
    }
  }
  for (std::size_t k = 0; k < grid.cells.size(); ++k) {
    grid.cells[k] = occupied[k] ? CellState::kOccupied : (known[k] ? CellState::kFree : CellState::kUnknown);
  }
  return grid;
}

OccupancySnapshot OccupancyMap::Snapshot(const geometry::Aabb3& box) const {
  OccupancySnapshot snap;
  const double res = options_.resolution_m;
  snap.voxel_size_m = res;
  if (box.Empty()) return snap;
  // Voxels aligned to multiples of the resolution, as OctoMap's.
  const Eigen::Vector3d lo = (box.min_m / res).array().floor() * res;
  const Eigen::Vector3i n = ((box.max_m - lo) / res).array().ceil().cast<int>().max(1);
  if (static_cast<std::size_t>(n.x()) * n.y() * n.z() > limits::kMaxOccupancySnapshotCells) {
    throw InputError("OccupancyMap::Snapshot: box too large for a dense grid");
  }
  snap.origin_world = lo;
  snap.nx = n.x();
  snap.ny = n.y();
  snap.nz = n.z();
  snap.cells.assign(static_cast<std::size_t>(n.x()) * n.y() * n.z(), Occupancy::kUnknown);
  const octomap::OcTree& tree = impl_->tree;
  const octomap::point3d bbx_min(lo.x(), lo.y(), lo.z());
  const octomap::point3d bbx_max(lo.x() + n.x() * res, lo.y() + n.y() * res, lo.z() + n.z() * res);
  for (auto it = tree.begin_leafs_bbx(bbx_min, bbx_max), end = tree.end_leafs_bbx(); it != end; ++it) {
    const octomap::point3d c = it.getCoordinate();
    const double half = 0.5 * it.getSize();
    const Occupancy state = tree.isNodeOccupied(*it) ? Occupancy::kOccupied : Occupancy::kFree;
    int i0[3], i1[3];
    const int dims[3] = {n.x(), n.y(), n.z()};
    for (int a = 0; a < 3; ++a) LeafCellRange(c(a), half, lo(a), res, dims[a], &i0[a], &i1[a]);
    for (int z = i0[2]; z <= i1[2]; ++z)
      for (int y = i0[1]; y <= i1[1]; ++y)
        for (int x = i0[0]; x <= i1[0]; ++x) snap.cells[snap.Index(x, y, z)] = state;
  }
  return snap;
}

}  // namespace objscan::mapping
