#pragma once
// The layout shared by the lazily built grids over a point set (DistanceGrid, NearestGrid): the
// points' bounds grown by a padding, covered by a regular grid whose spacing grows until the grid
// fits a size budget.
#include <Eigen/Core>
#include <vector>

namespace objscan::recognition {

struct GridFit {
  Eigen::Vector3f origin = Eigen::Vector3f::Zero();  // low corner of the grown bounds
  float spacing_m = 0.f;
  int nx = 0, ny = 0, nz = 0;  // per axis floor(extent / spacing) + extra_per_axis
};

// `points` must not be empty. The spacing starts at max(min_spacing_m, cbrt(volume / max_count)) and
// grows by 5% until nx * ny * nz <= max_count.
GridFit FitGrid(const std::vector<Eigen::Vector3f>& points, float padding_m, int max_count, float min_spacing_m,
                int extra_per_axis);

}  // namespace objscan::recognition
