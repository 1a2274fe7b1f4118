#pragma once
// Quality of a segmentation against ground truth: the Rand Index (exact, from the contingency
// table) and purity. The pre-segmentation measures of run.json (preseg_purity, rand_index_preseg)
// are computed on the map elements' majority ground-truth instances (evaluation only:
// eval/ground_truth_votes.h), which the caller passes in.
#include <cstdint>
#include <vector>

#include "objscan/mapping/surface_map.h"

namespace objscan::segmentation {

// Rand Index of two labelings of the same n points: the share of the n(n-1)/2 point pairs on which
// they agree (both together or both apart). Computed exactly from the contingency table in
// O(n + cells). 1.0 for n < 2. Throws std::invalid_argument on a size mismatch.
double RandIndex(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b);

// Point-weighted purity of `predicted` against `truth`: the share of points that belong to the
// majority truth label of their predicted cluster. 1.0 for n = 0.
double Purity(const std::vector<std::int32_t>& predicted, const std::vector<std::int32_t>& truth);

struct PresegQuality {
  double preseg_purity = 1.0;
  double rand_index_preseg = 1.0;
  std::size_t num_points = 0;
  std::size_t num_components = 0;
};

// Over the labelled elements that are neither tagged structural by the method nor ground-truth
// structure (instances listed in `structural_instances`, e.g. floor and walls), and not of
// instance 0 (no object). `element_instance[i]` is element i's ground-truth instance (elements
// beyond its size count as instance 0).
PresegQuality EvaluatePresegmentation(const mapping::SurfaceMap& map, const std::vector<std::int32_t>& element_instance,
                                      const std::vector<std::int32_t>& structural_instances);

}  // namespace objscan::segmentation
