#pragma once
// Free / occupied / unknown space (OctoMap behind a pImpl) at 5 cm, fed with subsampled depth rays.
// Feeds the 2-D navigation grid, view validity and the coverage metric.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/geometry/aabb.h"
#include "objscan/platform/depth_frame.h"
#include "objscan/navigation/occupancy_source.h"

namespace objscan::mapping {

struct OccupancyMapOptions {
  double resolution_m = 0.05;
  int pixel_stride = 8;            // one ray per stride x stride pixels
  double max_range_m = 4.0;        // rays are clipped here (OctoMap's maxrange)
  double prob_hit = 0.7;
  double prob_miss = 0.4;
  double clamping_min = 0.12;
  double clamping_max = 0.97;
  double occupied_threshold = 0.5;
  // View validity: the camera's voxel and the 6 points this far from it along the axes must be
  // known free (0 = the camera's voxel only).
  double view_clearance_m = 0.0;
  // End points lower than this (world z; the robot stands on the floor at z = 0) are the floor it
  // drives on: their rays clear space up to this height but mark nothing occupied, so floor noise
  // never becomes an obstacle. 0 = plain OctoMap (every end point is a hit).
  double floor_clearance_m = 0.05;

  template <class V>
  void Visit(V& v) {
    v("resolution_m", resolution_m);
    v("pixel_stride", pixel_stride);
    v("max_range_m", max_range_m);
    v("prob_hit", prob_hit);
    v("prob_miss", prob_miss);
    v("clamping_min", clamping_min);
    v("clamping_max", clamping_max);
    v("occupied_threshold", occupied_threshold);
    v("view_clearance_m", view_clearance_m);
    v("floor_clearance_m", floor_clearance_m);
  }
  void Validate() const;
};

enum class Occupancy : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

// The map's state over a box as a flat voxel array (x fastest) at the map's resolution, for lookups
// in hot loops (an octree descent per lookup costs ~50x more).
struct OccupancySnapshot {
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();  // min corner of voxel (0, 0, 0)
  double voxel_size_m = 0.05;
  int nx = 0, ny = 0, nz = 0;
  std::vector<Occupancy> cells;

  // kUnknown outside the box.
  Occupancy At(const Eigen::Vector3f& p_world) const {
    std::size_t index = 0;
    return IndexOf(p_world, &index) ? cells[index] : Occupancy::kUnknown;
  }
  // The index of the voxel holding p; false when p is outside the box (or not finite).
  bool IndexOf(const Eigen::Vector3f& p_world, std::size_t* index) const {
    const double inv = 1.0 / voxel_size_m;
    const double gx = (p_world.x() - origin_world.x()) * inv, gy = (p_world.y() - origin_world.y()) * inv,
                 gz = (p_world.z() - origin_world.z()) * inv;
    if (!(gx >= 0 && gy >= 0 && gz >= 0 && gx < nx && gy < ny && gz < nz)) return false;
    // Non-negative here, so truncation is floor.
    *index = Index(static_cast<int>(gx), static_cast<int>(gy), static_cast<int>(gz));
    return true;
  }
  bool Contains(int x, int y, int z) const { return x >= 0 && y >= 0 && z >= 0 && x < nx && y < ny && z < nz; }
  std::size_t Index(int x, int y, int z) const {
    return static_cast<std::size_t>(x) + static_cast<std::size_t>(nx) * (static_cast<std::size_t>(y) + static_cast<std::size_t>(ny) * z);
  }
};

class OccupancyMap : public navigation::OccupancySource {
 public:
  explicit OccupancyMap(const OccupancyMapOptions& options = OccupancyMapOptions());
  ~OccupancyMap() override;
  OccupancyMap(const OccupancyMap&) = delete;
  OccupancyMap& operator=(const OccupancyMap&) = delete;

  // Inserts the rays of every pixel_stride-th valid pixel (free along the ray, occupied at the end).
  void Integrate(const platform::DepthFrame& frame);
  // Inserts rays from `origin` to world points (already subsampled).
  void InsertRays(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3f>& end_points);

  Occupancy Query(const Eigen::Vector3d& p) const;
  // A camera in occupied or unknown space (or within view_clearance_m of either) is invalid.
  bool IsViewValid(const Eigen::Vector3d& camera_position) const;
  // Calls fn(center, size) for every occupied leaf (size is the leaf edge length in metres).
  void ForEachOccupied(const std::function<void(const Eigen::Vector3d& center, double size_m)>& fn) const;
  // Number of occupied voxels at the finest resolution.
  std::size_t NumOccupied() const;
  double resolution_m() const { return options_.resolution_m; }
  // Bounds of everything observed (free or occupied); empty before the first frame.
  geometry::Aabb3 KnownBounds() const;

  // The navigation grid (navigation::OccupancySource) over the known bounds: a cell is occupied when any
  // occupied voxel overlaps it within the height band (min_z_m, max_z_m) (e.g. floor + 5 cm to the
  // robot's height), unknown when no voxel of that band above it is known, else free.
  navigation::OccupancyGrid2D Grid(double min_z_m, double max_z_m, double cell_size_m) const override;
  // The same over the XY footprint of `bounds`.
  navigation::OccupancyGrid2D GridOver(const geometry::Aabb3& bounds, double min_z_m, double max_z_m,
                                double cell_size_m) const;

  // The voxels over `box` (grown to whole voxels); empty when the box is.
  OccupancySnapshot Snapshot(const geometry::Aabb3& box) const;
  const OccupancyMapOptions& options() const { return options_; }

 private:
  OccupancyMapOptions options_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace objscan::mapping
