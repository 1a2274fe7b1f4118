#include "objscan/recognition/spatial_bow.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace objscan::recognition {

void SpatialBowOptions::Validate() const {
  config::Require(height_bands >= 1, "recognition.bow.height_bands", "must be at least 1");
  config::Require(radial_rings >= 1, "recognition.bow.radial_rings", "must be at least 1");
  config::RequireNonNegative("recognition.bow.spatial_weight", spatial_weight);
}

int SpatialCell(const Eigen::Vector3f& p, const geometry::Aabb3& bounds, const SpatialBowOptions& options) {
  const Eigen::Vector3d size = bounds.Size();
  const Eigen::Vector3d c = bounds.Center();
  const double h = size.z() > 0.0 ? (p.z() - bounds.min_m.z()) / size.z() : 0.0;
  const int band = std::clamp(static_cast<int>(std::floor(h * options.height_bands)), 0, options.height_bands - 1);
  const double r_max = 0.5 * std::hypot(size.x(), size.y());
  const double r = std::hypot(p.x() - c.x(), p.y() - c.y());
  const double rr = r_max > 0.0 ? r / r_max : 0.0;
  const int ring = std::clamp(static_cast<int>(std::floor(rr * options.radial_rings)), 0, options.radial_rings - 1);
  return 1 + band * options.radial_rings + ring;
}

SparseHistogram ComputeSpatialBow(const Vocabulary& vocabulary, const std::vector<Eigen::Vector3f>& keypoints,
                                  const std::vector<float>& descriptors, const geometry::Aabb3& bounds,
                                  const SpatialBowOptions& options) {
  const int k = vocabulary.num_words();
  const int dim = vocabulary.dimension();
  std::map<std::uint32_t, double> global, cells;
  double global_total = 0.0, cell_total = 0.0;
  WordAssignment assigned[8];
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const int m = vocabulary.Assign(&descriptors[i * dim], assigned);
    if (m == 0) continue;
    const int cell = SpatialCell(keypoints[i], bounds, options);
    for (int a = 0; a < m; ++a) {
      global[static_cast<std::uint32_t>(assigned[a].word)] += assigned[a].weight;
      cells[static_cast<std::uint32_t>(cell * k + assigned[a].word)] += assigned[a].weight;
      global_total += assigned[a].weight;
      cell_total += assigned[a].weight;
    }
  }
  SparseHistogram h;
  h.reserve(global.size() + cells.size());
  for (const auto& [bin, v] : global) h.push_back({bin, static_cast<float>(v / global_total)});
  if (options.spatial_weight > 0.0) {
    for (const auto& [bin, v] : cells) h.push_back({bin, static_cast<float>(options.spatial_weight * v / cell_total)});
  }
  return h;  // global bins (< k) come first, then cells: increasing bin order
}

}  // namespace objscan::recognition
