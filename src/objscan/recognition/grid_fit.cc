#include "objscan/recognition/grid_fit.h"

#include <algorithm>
#include <cmath>

namespace objscan::recognition {

GridFit FitGrid(const std::vector<Eigen::Vector3f>& points, float padding_m, int max_count, float min_spacing_m,
                int extra_per_axis) {
  Eigen::Vector3f lo = points[0], hi = points[0];
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo.array() -= padding_m;
  hi.array() += padding_m;
  const Eigen::Vector3f extent = hi - lo;
  float spacing = std::max(min_spacing_m, std::cbrt(extent.prod() / static_cast<float>(max_count)));
  const auto count = [&](float e, float h) { return static_cast<int>(std::floor(e / h)) + extra_per_axis; };
  while (static_cast<long>(count(extent.x(), spacing)) * count(extent.y(), spacing) * count(extent.z(), spacing) >
         max_count)
    spacing *= 1.05f;
  GridFit fit;
  fit.origin = lo;
  fit.spacing_m = spacing;
  fit.nx = count(extent.x(), spacing);
  fit.ny = count(extent.y(), spacing);
  fit.nz = count(extent.z(), spacing);
  return fit;
}

}  // namespace objscan::recognition
