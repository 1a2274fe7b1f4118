#include "objscan/recognition/spatial_bow.h"

#include <algorithm>
#include <cmath>
#include <algorithm>
#include <map>

namespace objscan::recognition {

void SpatialBowOptions::Validate() const {
  // Upper bounds keep NumCells() (and a histogram's bin numbers) far from int overflow.
  config::Require(height_bands >= 1 && height_bands <= kMaxBandsOrRings, "recognition.bow.height_bands",
                  "must be in [1, " + std::to_string(kMaxBandsOrRings) + "]");
  config::Require(radial_rings >= 1 && radial_rings <= kMaxBandsOrRings, "recognition.bow.radial_rings",
                  "must be in [1, " + std::to_string(kMaxBandsOrRings) + "]");
  config::Require(absolute_height_edges_m.size() <= static_cast<std::size_t>(kMaxBandsOrRings),
                  "recognition.bow.absolute_height_edges_m",
                  "must have at most " + std::to_string(kMaxBandsOrRings) + " edges");
  config::RequireNonNegative("recognition.bow.spatial_weight", spatial_weight);
  for (std::size_t i = 0; i < absolute_height_edges_m.size(); ++i) {
    config::Require(i == 0 || absolute_height_edges_m[i] > absolute_height_edges_m[i - 1],
                    "recognition.bow.absolute_height_edges_m", "must increase");
  }
  config::RequireNonNegative("recognition.bow.absolute_weight", absolute_weight);
  config::RequireInRange("recognition.bow.up_normal_min_z", up_normal_min_z, 0.0, 1.0);
  config::RequireNonNegative("recognition.bow.size_weight", size_weight);
  config::Require(height_bin_ratio > 1.0, "recognition.bow.height_bin_ratio", "must be > 1");
  config::RequirePositive("recognition.bow.floor_gap_bin_m", floor_gap_bin_m);
}

namespace {

// Soft assignment of a continuous bin coordinate to its two nearest bins (linear weights).
void SoftBins(double coordinate, int num_bins, std::uint32_t first_bin, double weight, SparseHistogram* out) {
  const double c = std::clamp(coordinate, 0.0, static_cast<double>(num_bins - 1));
  const int lo = static_cast<int>(std::floor(c));
  const double frac = c - lo;
  out->push_back({first_bin + static_cast<std::uint32_t>(lo), static_cast<float>(weight * (1.0 - frac))});
  if (lo + 1 < num_bins && frac > 0.0)
    out->push_back({first_bin + static_cast<std::uint32_t>(lo + 1), static_cast<float>(weight * frac)});
}

}  // namespace

int AbsoluteCell(const Eigen::Vector3f& p, const Eigen::Vector3f& normal, const SpatialBowOptions& options) {
  const auto& edges = options.absolute_height_edges_m;
  const int band = static_cast<int>(std::upper_bound(edges.begin(), edges.end(), static_cast<double>(p.z())) - edges.begin());
  const int facing = normal.z() > options.up_normal_min_z ? 0 : (normal.z() < -options.up_normal_min_z ? 1 : 2);
  return 1 + options.NumRelativeCells() + 3 * band + facing;
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
                                  const std::vector<Eigen::Vector3f>& keypoint_normals,
                                  const std::vector<float>& descriptors, const geometry::Aabb3& bounds,
                                  const SpatialBowOptions& options) {
  const int k = vocabulary.num_words();
  const int dim = vocabulary.dimension();
  // Bins of each level; every keypoint adds the same total weight to each level, so one total
  // normalises all three.
  std::map<std::uint32_t, double> global, relative, absolute;
  double total = 0.0;
  WordAssignment assigned[8];
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const int m = vocabulary.Assign(&descriptors[i * dim], assigned);
    if (m == 0) continue;
    const int cell = SpatialCell(keypoints[i], bounds, options);
    const Eigen::Vector3f n = i < keypoint_normals.size() ? keypoint_normals[i] : Eigen::Vector3f::Zero();
    const int abs_cell = AbsoluteCell(keypoints[i], n, options);
    for (int a = 0; a < m; ++a) {
      const auto word = static_cast<std::uint32_t>(assigned[a].word);
      global[word] += assigned[a].weight;
      relative[static_cast<std::uint32_t>(cell * k) + word] += assigned[a].weight;
      absolute[static_cast<std::uint32_t>(abs_cell * k) + word] += assigned[a].weight;
      total += assigned[a].weight;
    }
  }
  SparseHistogram h;
  if (!(total > 0.0)) return h;
  h.reserve(global.size() + relative.size() + absolute.size());
  auto emit = [&](const std::map<std::uint32_t, double>& level, double weight) {
    if (weight <= 0.0) return;
    for (const auto& [bin, v] : level) h.push_back({bin, static_cast<float>(weight * v / total)});
  };
  // Levels occupy increasing bin ranges, so the result is sorted.
  emit(global, 1.0);
  emit(relative, options.spatial_weight);
  emit(absolute, options.absolute_weight);
  if (options.size_weight > 0.0 && !bounds.Empty()) {
    const std::uint32_t first = static_cast<std::uint32_t>(k * options.NumCells());
    const double height = std::max(bounds.Size().z(), 0.05);
    SoftBins(std::log(height / 0.05) / std::log(options.height_bin_ratio), SpatialBowOptions::kHeightBins, first,
             options.size_weight, &h);
    SoftBins(std::max(0.0, bounds.min_m.z()) / options.floor_gap_bin_m, SpatialBowOptions::kFloorGapBins,
             first + SpatialBowOptions::kHeightBins, options.size_weight, &h);
  }
  return h;
}

}  // namespace objscan::recognition
