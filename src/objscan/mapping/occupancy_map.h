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
#include "objscan/sim/depth_frame.h"

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
  // View validity: the camera and its sphere of this radius must be known free.
  double view_clearance_m = 0.1;

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
  }
  void Validate() const;
};

enum class Occupancy : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

// A 2-D grid over the XY plane. Cell (ix, iy) covers [origin + ix*res, origin + (ix+1)*res) etc.
struct NavigationGrid {
  enum Cell : std::uint8_t { kUnknown = 0, kFree = 1, kObstacle = 2 };
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  double resolution_m = 0.05;
  int width = 0;   // cells along X
  int height = 0;  // cells along Y
  std::vector<std::uint8_t> cells;  // row-major: index = iy * width + ix

  bool InBounds(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
  std::uint8_t At(int ix, int iy) const { return cells[static_cast<std::size_t>(iy) * width + ix]; }
  // Cell of a world point (may be out of bounds).
  void CellOf(const Eigen::Vector2d& p, int* ix, int* iy) const;
  Eigen::Vector2d CenterOf(int ix, int iy) const;
  // Free for navigation (unknown and obstacle cells are blocked).
  bool IsFree(const Eigen::Vector2d& p) const;
};

struct NavigationGridOptions {
  double floor_height_m = 0.0;
  // Occupied voxels between floor + clearance and robot height are obstacles.
  double floor_clearance_m = 0.05;
  double robot_height_m = 1.5;
  template <class V>
  void Visit(V& v) {
    v("floor_height_m", floor_height_m);
    v("floor_clearance_m", floor_clearance_m);
    v("robot_height_m", robot_height_m);
  }
  void Validate() const;
};

class OccupancyMap {
 public:
  explicit OccupancyMap(const OccupancyMapOptions& options = OccupancyMapOptions());
  ~OccupancyMap();
  OccupancyMap(const OccupancyMap&) = delete;
  OccupancyMap& operator=(const OccupancyMap&) = delete;

  // Inserts the rays of every pixel_stride-th valid pixel (free along the ray, occupied at the end).
  void Integrate(const sim::DepthFrame& frame);
  // Inserts rays from `origin` to world points (already subsampled).
  void InsertRays(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3f>& end_points);

  Occupancy Query(const Eigen::Vector3d& p) const;
  // A camera in occupied or unknown space (or closer than view_clearance_m to either) is invalid.
  bool IsViewValid(const Eigen::Vector3d& camera_position) const;
  // Calls fn(center, size) for every occupied leaf (size is the leaf edge length in metres).
  void ForEachOccupied(const std::function<void(const Eigen::Vector3d& center, double size_m)>& fn) const;
  // Number of occupied voxels at the finest resolution.
  std::size_t NumOccupied() const;
  double resolution_m() const { return options_.resolution_m; }
  // Bounds of everything observed (free or occupied); empty before the first frame.
  geometry::Aabb3 KnownBounds() const;

  // The 2-D grid over `bounds_xy` (min, max) or, when empty, the known bounds: a cell is an obstacle
  // when any voxel of its column between floor + clearance and robot height is occupied, unknown
  // when no voxel of that band is known, else free.
  NavigationGrid ToNavigationGrid(const NavigationGridOptions& options,
                                  const geometry::Aabb3& bounds = geometry::Aabb3()) const;

  const OccupancyMapOptions& options() const { return options_; }

 private:
  OccupancyMapOptions options_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace objscan::mapping
