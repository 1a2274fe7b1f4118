#include "objscan/recognition/distance_grid.h"

#include <algorithm>
#include <cmath>

#include "objscan/recognition/grid_fit.h"

namespace objscan::recognition {

DistanceGrid::DistanceGrid(const std::vector<Eigen::Vector3f>& points, float truncation_m, int max_vertices,
                           float min_spacing_m) {
  if (points.empty() || !(truncation_m > 0.f) || max_vertices < 8) return;
  const GridFit fit = FitGrid(points, truncation_m, max_vertices, min_spacing_m, 2);
  const float spacing = fit.spacing_m;
  nx_ = fit.nx;
  ny_ = fit.ny;
  nz_ = fit.nz;
  max_cell_x_ = static_cast<float>(nx_ - 1);
  max_cell_y_ = static_cast<float>(ny_ - 1);
  max_cell_z_ = static_cast<float>(nz_ - 1);
  origin_ = fit.origin;
  spacing_m_ = spacing;
  inv_spacing_ = 1.f / spacing;
  truncation_m_ = truncation_m;
  step_m_ = truncation_m / 255.f;

  // Splat each point into the vertices within the truncation distance (exact squared distances).
  const float t2 = truncation_m * truncation_m;
  std::vector<float> d2(static_cast<std::size_t>(nx_) * ny_ * nz_, t2);
  const int reach = static_cast<int>(std::ceil(truncation_m * inv_spacing_));
  for (const auto& p : points) {
    const Eigen::Vector3f g = (p - origin_) * inv_spacing_;
    const int cy = static_cast<int>(std::lround(g.y())),
              cz = static_cast<int>(std::lround(g.z()));
    for (int z = std::max(0, cz - reach); z <= std::min(nz_ - 1, cz + reach); ++z) {
      const float dz = origin_.z() + z * spacing - p.z();
      for (int y = std::max(0, cy - reach); y <= std::min(ny_ - 1, cy + reach); ++y) {
        const float dy = origin_.y() + y * spacing - p.y();
        const float dyz2 = dy * dy + dz * dz;
        if (dyz2 >= t2) continue;
        float* row = d2.data() + (static_cast<std::size_t>(z) * ny_ + y) * nx_;
        // Only the vertices of this row inside the truncation sphere.
        const float half_width = std::sqrt(t2 - dyz2) * inv_spacing_;
        const int x_lo = std::max(0, static_cast<int>(std::ceil(g.x() - half_width)));
        const int x_hi = std::min(nx_ - 1, static_cast<int>(std::floor(g.x() + half_width)));
        for (int x = x_lo; x <= x_hi; ++x) {
          const float dx = origin_.x() + x * spacing - p.x();
          row[x] = std::min(row[x], dx * dx + dyz2);
        }
      }
    }
  }
  values_.resize(d2.size());
  for (std::size_t i = 0; i < d2.size(); ++i) {
    values_[i] = static_cast<std::uint8_t>(std::min(255.f, std::round(std::sqrt(d2[i]) / step_m_)));
  }
}

void DistanceGrid::Distances(const Eigen::Vector3f* q, std::size_t n, float* distance) const {
  for (std::size_t k = 0; k < n; ++k) distance[k] = Distance(q[k]);
}

}  // namespace objscan::recognition
