#pragma once
// Spatially sensitive bag of words (paper §4.2): word histograms per spatial cell of the item's upright
// frame, so that two shapes with the same local parts in different places differ. Gravity is known, so
// the frame is the axis-aligned box of the points: height bands relative to the box, and rings of
// horizontal distance from the box's vertical axis (yaw does not matter). A global level (all
// keypoints) is kept beside the cells, like a two-level spatial pyramid, so a partial view whose box
// is cut still matches on its words.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "objscan/common/config.h"
#include "objscan/geometry/aabb.h"
#include "objscan/recognition/vocabulary.h"

namespace objscan::recognition {

struct SpatialBowOptions {
  int height_bands = 3;
  int radial_rings = 2;
  double spatial_weight = 1.0;  // weight of the cell level against the global level

  template <class V>
  void Visit(V& v) {
    v("height_bands", height_bands);
    v("radial_rings", radial_rings);
    v("spatial_weight", spatial_weight);
  }
  void Validate() const;
  int NumCells() const { return 1 + height_bands * radial_rings; }
};

struct HistogramBin {
  std::uint32_t bin = 0;  // cell * num_words + word
  float value = 0.f;
};
// Non-zero bins in increasing bin order.
using SparseHistogram = std::vector<HistogramBin>;

// Spatial cell (1 .. height_bands*radial_rings) of a point in the frame given by `bounds`.
int SpatialCell(const Eigen::Vector3f& p, const geometry::Aabb3& bounds, const SpatialBowOptions& options);

// Histogram of the keypoints' soft word assignments; each level is L1-normalised (the cell level then
// scaled by spatial_weight). `descriptors` is keypoints.size() x vocabulary.dimension().
SparseHistogram ComputeSpatialBow(const Vocabulary& vocabulary, const std::vector<Eigen::Vector3f>& keypoints,
                                  const std::vector<float>& descriptors, const geometry::Aabb3& bounds,
                                  const SpatialBowOptions& options);

}  // namespace objscan::recognition
